//! DPD-Trotter: the pairwise sweep T solves the conservative pair force and the
//! Ornstein-Uhlenbeck pair update together, exactly per pair. Pairwise: total momentum is
//! conserved to rounding error. As gamma grows the exact pair relaxation swamps the
//! conservative force and these schemes degrade.

use dpd_core::Scheme;
use dpd_macros::dpd_scheme;

/// SAS (DPD-Trotter), written `TAT` here (S names compositions in the scheme language).
///
/// ```text
/// T>(1/2) A(1) T<(1/2)
/// ```
///
/// Each T sweep evaluates its pair forces inline: two force evaluations and one pair-distance
/// evaluation per step. Deterministic order 2, invariant measure order 2, symmetric. Source:
/// T. Serrano, G. De Fabritiis, P. Español and P. V. Coveney, "A stochastic Trotter
/// integration scheme for dissipative particle dynamics", Math. Comput. Simul. 72, 190 (2006).
pub fn sas() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!("TAT", name = "sas", order >= 2, invariant_order >= 2)
}

/// ASA: the other symmetric arrangement of the same pieces.
///
/// ```text
/// A(1/2) T(1) A(1/2)
/// ```
///
/// One force and one pair-distance evaluation per step. Deterministic order 2, but first order
/// for the invariant measure: a pair generator `B_k + O_k` of T does not annihilate the Gibbs
/// density on its own (only their sum with A does), and a single sweep visits the pairs in one
/// order, which SAS mirrors and ASA does not. Source: the other ordering of Serrano et al.
/// (2006).
pub fn asa() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!("ATA", name = "asa", order >= 2, invariant_order >= 1)
}
