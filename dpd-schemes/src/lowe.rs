//! Splittings thermostatted by Lowe-Andersen pairwise collisions (the L letter, algorithms.md
//! section 2) instead of the pairwise friction of O. They need a collision frequency
//! (`collision_rate`) on the system; their cost and orders are claimed in the
//! [`registry`](crate::registry).

use dpd_core::Scheme;
use dpd_macros::dpd_scheme;

/// Lowe's scheme: velocity Verlet with the conservative force, then a collision sweep.
///
/// ```text
/// B(1/2) A(1) B(1/2) L(1)
/// ```
///
/// Source: C. P. Lowe, "An alternative approach to dissipative particle dynamics", Europhys.
/// Lett. 47, 145 (1999), with the collision probability `1 - exp(-Gamma dt)` for his
/// `Gamma dt`.
pub fn lowe_andersen() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!("B A B L", name = "lowe-andersen")
}

/// The ABOBA ordering with collisions in place of the O sweep: the kicks and the sweep share
/// the half-step positions.
///
/// ```text
/// A(1/2) B(1/2) L(1) B(1/2) A(1/2)
/// ```
///
/// Source: this crate (issue 49), ABOBA of X. Shang, SIAM J. Sci. Comput. 43, A1929 (2021).
pub fn ablba() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!("ABLBA", name = "ablba")
}
