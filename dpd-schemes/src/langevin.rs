//! Splittings of the exact sub-flows A, B and the pairwise exact O, in the orders known from
//! Langevin dynamics. Their cost and orders are claimed in the [`registry`](crate::registry)
//! (algorithms.md section 4 for the analysis).

use dpd_core::Scheme;
use dpd_macros::dpd_scheme;

/// ABOBA with exact pairwise O.
///
/// ```text
/// A(1/2) B(1/2) O(1) B(1/2) A(1/2)
/// ```
///
/// The two kicks and the sweep share one pair and force evaluation at the half-step positions.
/// Source: X. Shang, "Accurate and efficient splitting methods for
/// dissipative particle dynamics", SIAM J. Sci. Comput. 43, A1929 (2021).
pub fn aboba() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!("ABOBA", name = "aboba")
}

/// BAOAB with exact pairwise O.
///
/// ```text
/// B(1/2) A(1/2) O(1) A(1/2) B(1/2)
/// ```
///
/// The sweep needs the pair geometry at the half-step positions and the kick the forces at the
/// new ones. Source: B. Leimkuhler and C. Matthews, "Rational construction of
/// stochastic numerical methods for molecular sampling", AMRX 2013, 34 (Langevin dynamics),
/// with the pairwise DPD sweep of Shang (2021).
pub fn baoab() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!("BAOAB", name = "baoab")
}

/// BAOOAB: BAOAB with the sweep split in two halves, the second visiting the pairs in reverse,
/// so that the step is symmetric also in its pair order.
///
/// ```text
/// B(1/2) A(1/2) O>(1/2) O<(1/2) A(1/2) B(1/2)
/// ```
///
/// Source: algorithms.md section 3 (BAOAB of Leimkuhler and Matthews 2013 with
/// mirrored pairwise sweeps).
pub fn baooab() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!("BAOOAB", name = "baooab")
}

/// OBABO with exact pairwise O: velocity Verlet between two half sweeps, the second one
/// reversed.
///
/// ```text
/// O>(1/2) B(1/2) A(1) B(1/2) O<(1/2)
/// ```
///
/// Source: G. Bussi and M. Parrinello, Phys. Rev. E 75, 056707 (2007)
/// (Langevin dynamics); the exact-O form of DPD-S2.
pub fn obabo() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!("OBABO", name = "obabo")
}
