//! Peters' scheme: velocity Verlet with the conservative force, then Peters' pairwise
//! thermostat, which is the exact pair Ornstein-Uhlenbeck sweep O (docs/design-search.md has
//! the algebra). Its cost and orders are claimed in the [`registry`](crate::registry).

use dpd_core::Scheme;
use dpd_macros::dpd_scheme;

/// Peters' scheme as DL_MESO runs it: velocity Verlet with the conservative force in place of
/// the full DPD force, then one sweep of the pairs that replaces each pair's relative normal
/// velocity `u` by the exact solution of its Ornstein-Uhlenbeck process over the step,
/// `u exp(-tau dt) + sqrt(kbt mu (1 - exp(-2 tau dt))) R` (`tau = gamma w_D mu`, `mu` the
/// inverse reduced mass): O's update.
///
/// ```text
/// B(1/2) A(1) B(1/2) O(1)
/// ```
///
/// Source: E. A. J. F. Peters, "Elimination of time step effects in DPD", Europhys. Lett. 66,
/// 311 (2004) (abstract only reachable here; the update as Atomistica's Peters thermostat
/// computes it).
pub fn peters() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!("B A B O", name = "peters")
}
