//! Exponential-time-differencing schemes for small masses (algorithms.md section 5): per
//! particle and Cartesian component, the velocity equation `du/dt + c u = a + b xi` with `c`,
//! `a` and `b` frozen over the step is solved exactly, which stays stable when the relaxation
//! rate `c ~ gamma / m` is large. Not splittings of exact flows, and not pairwise: total
//! momentum is conserved on average only (see `dpd_core::flow::exponential_velocity`).

use dpd_core::flow::{drift, exponential_velocity, EtdNoise};
use dpd_core::{Scheme, System};

/// SETD: the exponential velocity update with the exact Ornstein-Uhlenbeck variance, then the
/// drift with the new velocity.
///
/// ```text
/// E(1) A(1)      E: u_new = u + dt phi1(c dt) g + sqrt(dt phi1(2 c dt)) b xi   (stream 0)
///                A: q += dt v_new
/// ```
///
/// Forces, dissipative couplings and rates are evaluated at the start of the step. The source
/// leaves the position update implicit; the drift with the new velocity makes the
/// deterministic part (`gamma = 0`, where `c = 0`) the symplectic Euler method; of the
/// alternatives tried against the source's tables at `m = 0.01` (old velocity, mean of old and
/// new, exact integral of the frozen equation; docs/papers.md, 002) none matches them better
/// across the steps.
/// Source: N. Phan-Thien, N. Mai-Duy, D. Pan and B. C. Khoo, "Exponential-time
/// differencing schemes for low-mass DPD systems", Comput. Phys. Commun. 185, 229 (2014),
/// who recommend `c dt < 1`.
#[derive(Clone, Copy, Debug, Default)]
pub struct Setd;

impl Scheme for Setd {
    fn name(&self) -> &str {
        "setd"
    }
    fn step(&self, sys: &mut System) {
        let dt = sys.dt();
        exponential_velocity(sys, dt, 0, EtdNoise::Exact);
        drift(sys, dt);
    }
}

/// MSETD: as [`Setd`], with the random force frozen over the step like the deterministic
/// one, so its variance factor is `(1 - exp(-c dt))^2 / (c^2 dt)` instead of
/// `(1 - exp(-2 c dt)) / (2 c)` (equal for small `c dt`, smaller near `c dt = 1`).
///
/// ```text
/// E'(1) A(1)     E': u_new = u + dt phi1(c dt) g + sqrt(dt) phi1(c dt) b xi   (stream 0)
///                A:  q += dt v_new
/// ```
///
/// Source: Phan-Thien, Mai-Duy, Pan and Khoo,
/// Comput. Phys. Commun. 185, 229 (2014).
#[derive(Clone, Copy, Debug, Default)]
pub struct Msetd;

impl Scheme for Msetd {
    fn name(&self) -> &str {
        "msetd"
    }
    fn step(&self, sys: &mut System) {
        let dt = sys.dt();
        exponential_velocity(sys, dt, 0, EtdNoise::Frozen);
        drift(sys, dt);
    }
}
