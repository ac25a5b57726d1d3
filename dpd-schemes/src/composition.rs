//! Yoshida's fourth-order triple jump for the Hamiltonian part, composed symmetrically with
//! the exact pairwise O. Their cost and orders are claimed in the [`registry`](crate::registry).
//!
//! `Y(c) = S(x1 c) S(x0 c) S(x1 c)` with `S(c) = B(c/2) A(c) B(c/2)`,
//! `x1 = 1/(2 - 2^(1/3))`, `x0 = -2^(1/3)/(2 - 2^(1/3))` (H. Yoshida, Phys. Lett. A 150, 262
//! (1990)).

use dpd_core::Scheme;
use dpd_macros::dpd_scheme;

/// ABOBA-like: half a triple jump, the sweep, the other half.
///
/// ```text
/// Y(1/2) O(1) Y(1/2)      (B A B A B A B) O (B A B A B A B)
/// ```
///
/// The kicks next to the sweep share its positions, so as in ABOBA O sits between two kicks.
/// Source: this crate (the high-order ABOBA variant of issue 5).
pub fn aboba_y4() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!(
        "S(x1/2) S(x0/2) S(x1/2) O S(x1/2) S(x0/2) S(x1/2)",
        name = "aboba-y4"
    )
}

/// OBABO-like: the whole triple jump between two half sweeps (M-Shardlow-2 with exact,
/// symmetrically placed sweeps).
///
/// ```text
/// O>(1/2) Y(1) O<(1/2)
/// ```
///
/// Half the cost of [`aboba_y4`] for the same orders. Source: this crate.
pub fn obabo_y4() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!("O(1/2) S(x1) S(x0) S(x1) O(1/2)", name = "obabo-y4")
}
