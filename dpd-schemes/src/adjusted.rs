//! Metropolis-adjusted splittings (generalised hybrid Monte Carlo, the braces of algorithms.md
//! section 2): the Hamiltonian part in braces is accepted or rejected on its energy error, so
//! the step samples the Gibbs measure exactly at any dt. A rejection negates every momentum,
//! the total momentum too; their cost and orders (those of the unadjusted word) are claimed in
//! the [`registry`](crate::registry).

use dpd_core::Scheme;
use dpd_macros::dpd_scheme;

/// Velocity Verlet in braces, then the exact pairwise O sweep: ABOBA observed after its
/// kicks, adjusted.
///
/// ```text
/// { B(1/2) A(1) B(1/2) } O(1)
/// ```
///
/// Source: generalised hybrid Monte Carlo (A. M. Horowitz, Phys. Lett. B 268, 247 (1991));
/// the pairwise O sweep and the spelling are this crate's (issue 49).
pub fn ghmc() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!("{B(1/2) A B(1/2)} O", name = "ghmc")
}
