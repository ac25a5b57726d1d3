//! Splittings thermostatted by the pairwise adaptive Langevin thermostat (PAdL: the Oa sweep
//! at friction `xi gamma_ij` and the Xi update of `xi`, algorithms.md section 2) and by the
//! pairwise Nose-Hoover-Langevin thermostat (PNHL: the noiseless On sweep, and Xi with the
//! Langevin friction `thermostat_friction` of `xi`). They need a thermostat mass
//! (`thermostat_mass`) on the system; their cost and orders are claimed in the
//! [`registry`](crate::registry).

use dpd_core::Scheme;
use dpd_macros::dpd_scheme;

/// PAdL in the BAOAB ordering, xi updated in two halves around the adaptive sweep.
///
/// ```text
/// B(1/2) A(1/2) Xi(1/2) Oa(1) Xi(1/2) A(1/2) B(1/2)
/// ```
///
/// Source: B. Leimkuhler and X. Shang, J. Comput. Phys. 324, 174 (2016), whose equations are
/// these; their full text was not reached here, so the ordering is this crate's (issue 49).
pub fn padl() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!("B A Xi(1/2) Oa Xi(1/2) A B", name = "padl")
}

/// PAdL in the ABOBA ordering: the kicks, the sweep and the updates of xi share the half-step
/// positions.
///
/// ```text
/// A(1/2) B(1/2) Xi(1/2) Oa(1) Xi(1/2) B(1/2) A(1/2)
/// ```
///
/// Source: this crate (issue 49), ABOBA of X. Shang, SIAM J. Sci. Comput. 43, A1929 (2021).
pub fn padl_aboba() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!(
        "A(1/2) B(1/2) Xi(1/2) Oa Xi(1/2) B(1/2) A(1/2)",
        name = "padl-aboba"
    )
}

/// PNHL in PAdL's BAOAB ordering: the pair sweep without noise at friction `xi gamma_ij`, xi
/// updated (with its Langevin part) in two halves around it.
///
/// ```text
/// B(1/2) A(1/2) Xi(1/2) On(1) Xi(1/2) A(1/2) B(1/2)
/// ```
///
/// Source: B. Leimkuhler and X. Shang, J. Comput. Phys. 280, 72 (2015), of which only the
/// abstract was reached here: the equations are derived in dpd-core's `flow::adaptive`, the
/// ordering is [`padl`]'s (issue 49).
pub fn pnhl() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!("B A Xi(1/2) On Xi(1/2) A B", name = "pnhl")
}
