//! Shardlow's splittings with the BBK pair update, and the M-Shardlow compositions that put a
//! Yoshida triple jump in front of the sweep. Their cost and orders are claimed in the
//! [`registry`](crate::registry).

use dpd_core::Scheme;
use dpd_macros::dpd_scheme;

/// DPD-S1: one BBK sweep, then velocity Verlet for the conservative part.
///
/// ```text
/// Ob(1) B(1/2) A(1) B(1/2)
/// ```
///
/// The BBK update is weakly second order, yet keeps each pair's Maxwellian exactly, so the
/// invariant-measure order is that of `O B A B`: 2. Source: T. Shardlow, "Splitting for dissipative particle dynamics", SIAM J.
/// Sci. Comput. 24, 1267 (2003).
pub fn dpd_s1() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!("ObBAB", name = "dpd-s1")
}

/// DPD-S2: the BBK sweep split around velocity Verlet, the second half reversed.
///
/// ```text
/// Ob>(1/2) B(1/2) A(1) B(1/2) Ob<(1/2)
/// ```
///
/// Source: Shardlow (2003).
pub fn dpd_s2() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!("Ob(1/2) B A B Ob(1/2)", name = "dpd-s2")
}

/// M-Shardlow-1 as published: the Yoshida triple jump with the wrong sign of the inner step,
/// then one BBK sweep.
///
/// ```text
/// S(x1) S(-x0) S(x1) Ob(1),   S(c) = B(c/2) A(c) B(c/2),
/// x1 = 1/(2 - 2^(1/3)),  -x0 = +2^(1/3)/(2 - 2^(1/3))
/// ```
///
/// INCONSISTENT: the A and B coefficients sum to `2 x1 - x0 = 4.405`, not 1, so the
/// Hamiltonian part runs 4.4 times too long per step and the scheme has no order. Kept (with
/// `allow_inconsistent`) to reproduce the published error. Source: Yamada et al., as quoted in algorithms.md
/// section 3.
pub fn m_shardlow_1() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!(
        "S(x1) S(-x0) S(x1) Ob",
        name = "m-shardlow-1",
        allow_inconsistent
    )
}

/// M-Shardlow-2: the corrected composition, Yoshida's fourth-order triple jump for the
/// Hamiltonian part, then one BBK sweep.
///
/// ```text
/// S(x1) S(x0) S(x1) Ob(1),   S(c) = B(c/2) A(c) B(c/2),
/// x1 = 1/(2 - 2^(1/3)),  x0 = -2^(1/3)/(2 - 2^(1/3))
/// ```
///
/// The triple jump makes the Hamiltonian part fourth order, and since the BBK sweep keeps each
/// pair's Maxwellian exactly the invariant-measure order is 4 as well. Sources: Yamada et al. (algorithms.md
/// section 3); H. Yoshida, Phys. Lett. A 150, 262 (1990).
pub fn m_shardlow_2() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!("S(x1) S(x0) S(x1) Ob", name = "m-shardlow-2")
}
