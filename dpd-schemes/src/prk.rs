//! Third-order partitioned Runge-Kutta schemes: the published full-force form with the noise
//! frozen within the step, and forms that compose the same Hamiltonian sequence with the exact
//! pairwise O. Their cost and orders are claimed in the [`registry`](crate::registry).
//!
//! A table `(b1, b2, b3; bh1, bh2, bh3)` is the step
//! `K(b1) A(bh1) K(b2) A(bh2) K(b3) A(bh3)`; its order-3 conditions are the published
//! equations 12-16 of algorithms.md section 3.

use dpd_core::Scheme;
use dpd_macros::dpd_scheme;

/// PRK3 with Ruth's coefficients and the full-force kick, noise frozen within the step.
///
/// ```text
/// F(7/24) A(2/3) F(3/4) A(-2/3) F(-1/24) A(1)      all F on one random stream
/// ```
///
/// The invariant-measure criterion does not apply (F is not an exact flow). Sources: R. D. Ruth,
/// IEEE Trans. Nucl. Sci. 30, 2669 (1983); for DPD, "Temperature error reduction of DPD fluid
/// by using partitioned Runge-Kutta time integration scheme", Fluids 4, 156 (2019).
pub fn prk3_ruth() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!(
        "prk(b = [7/24, 3/4, -1/24], bh = [2/3, -2/3, 1])",
        name = "prk3-ruth"
    )
}

/// PRK3 with Iwatsu's solution A and the full-force kick, noise frozen within the step.
///
/// ```text
/// F(b1) A(bh1) F(11/12) A(bh2) F(b3) A(5/9),   r = sqrt(209/2), t = sqrt(38/11),
/// b1 = (-7 + r)/12, b3 = (8 - r)/12, bh1 = (2/9)(1 + t), bh2 = (2/9)(1 - t)
/// ```
///
/// Source: Iwatsu's third-order solutions as used
/// for DPD in Fluids 4, 156 (2019).
pub fn prk3_iwatsu_a() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!(
        "prk(b = [(-7 + sqrt(209/2))/12, 11/12, (8 - sqrt(209/2))/12], \
             bh = [(2/9)(1 + sqrt(38/11)), (2/9)(1 - sqrt(38/11)), 5/9])",
        name = "prk3-iwatsu-a"
    )
}

/// PRK3 with Iwatsu's solution B and the full-force kick, noise frozen within the step.
///
/// ```text
/// F(b1) A(bh1) F(11/12) A(bh2) F(b3) A(5/9),   r = sqrt(209/2), t = sqrt(38/11),
/// b1 = -(7 + r)/12, b3 = (8 + r)/12, bh1 = (2/9)(1 - t), bh2 = (2/9)(1 + t)
/// ```
///
/// Source: as [`prk3_iwatsu_a`].
pub fn prk3_iwatsu_b() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!(
        "prk(b = [-(7 + sqrt(209/2))/12, 11/12, (8 + sqrt(209/2))/12], \
             bh = [(2/9)(1 - sqrt(38/11)), (2/9)(1 + sqrt(38/11)), 5/9])",
        name = "prk3-iwatsu-b"
    )
}

/// Ruth's Hamiltonian sequence with exact kicks, followed by one exact pairwise O sweep.
///
/// ```text
/// B(7/24) A(2/3) B(3/4) A(-2/3) B(-1/24) A(1) O(1)
/// ```
///
/// Source: this crate, from
/// Ruth (1983) and the exact O of algorithms.md section 2.
pub fn prk3_ruth_o() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!(
        "prk(b = [7/24, 3/4, -1/24], bh = [2/3, -2/3, 1], kick = B) O",
        name = "prk3-ruth-o"
    )
}

/// Symmetric composition of Ruth's sequence `R` with its adjoint `R*` around one exact O
/// sweep, like ABOBA with a higher-order Hamiltonian half step on each side.
///
/// ```text
/// R(1/2) O(1) R*(1/2),   R(c)  = B(7c/24) A(2c/3) B(3c/4) A(-2c/3) B(-c/24) A(c),
///                        R*(c) = A(c) B(-c/24) A(-2c/3) B(3c/4) A(2c/3) B(7c/24)
/// ```
///
/// A third-order method composed with its adjoint is symmetric, hence of even order, which
/// raises both orders by one. The last kick's forces are reused by the first kick of the next
/// step; the sweep needs the geometry at the middle positions. Source:
/// this crate, from Ruth (1983) and the exact O of algorithms.md section 2.
pub fn prk3_ruth_sym() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!(
        "def R(c) = B(7c/24) A(2c/3) B(3c/4) A(-2c/3) B(-c/24) A(c); \
         def Radj(c) = A(c) B(-c/24) A(-2c/3) B(3c/4) A(2c/3) B(7c/24); \
         R(1/2) O Radj(1/2)",
        name = "prk3-ruth-sym"
    )
}
