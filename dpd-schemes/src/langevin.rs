//! Splittings of the exact sub-flows A, B and the pairwise exact O, in the orders known from
//! Langevin dynamics. All are pairwise (total momentum conserved to rounding error), symmetric,
//! deterministic order 2, and second order for the invariant measure by the left-ideal
//! criterion (algorithms.md section 4).

use dpd_core::Scheme;
use dpd_macros::dpd_scheme;

/// ABOBA with exact pairwise O.
///
/// ```text
/// A(1/2) B(1/2) O(1) B(1/2) A(1/2)
/// ```
///
/// The two kicks and the sweep share one pair and force evaluation at the half-step positions:
/// one force and one pair-distance evaluation per step. Deterministic order 2, invariant
/// measure order 2. Source: X. Shang, "Accurate and efficient splitting methods for
/// dissipative particle dynamics", SIAM J. Sci. Comput. 43, A1929 (2021).
pub fn aboba() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!("ABOBA", name = "aboba", order >= 2, invariant_order >= 2)
}

/// BAOAB with exact pairwise O.
///
/// ```text
/// B(1/2) A(1/2) O(1) A(1/2) B(1/2)
/// ```
///
/// The sweep needs the pair geometry at the half-step positions and the kick the forces at the
/// new ones: one force and two pair-distance evaluations per step. Deterministic order 2,
/// invariant measure order 2. Source: B. Leimkuhler and C. Matthews, "Rational construction of
/// stochastic numerical methods for molecular sampling", AMRX 2013, 34 (Langevin dynamics),
/// with the pairwise DPD sweep of Shang (2021).
pub fn baoab() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!("BAOAB", name = "baoab", order >= 2, invariant_order >= 2)
}

/// BAOOAB: BAOAB with the sweep split in two halves, the second visiting the pairs in reverse,
/// so that the step is symmetric also in its pair order.
///
/// ```text
/// B(1/2) A(1/2) O>(1/2) O<(1/2) A(1/2) B(1/2)
/// ```
///
/// One force and two pair-distance evaluations per step. Deterministic order 2, invariant
/// measure order 2. Source: algorithms.md section 3 (BAOAB of Leimkuhler and Matthews 2013 with
/// mirrored pairwise sweeps).
pub fn baooab() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!("BAOOAB", name = "baooab", order >= 2, invariant_order >= 2)
}

/// OBABO with exact pairwise O: velocity Verlet between two half sweeps, the second one
/// reversed.
///
/// ```text
/// O>(1/2) B(1/2) A(1) B(1/2) O<(1/2)
/// ```
///
/// One force and one pair-distance evaluation per step. Deterministic order 2, invariant
/// measure order 2. Source: G. Bussi and M. Parrinello, Phys. Rev. E 75, 056707 (2007)
/// (Langevin dynamics); the exact-O form of DPD-S2.
pub fn obabo() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!("OBABO", name = "obabo", order >= 2, invariant_order >= 2)
}
