//! DPD-Trotter: the pairwise sweep T solves the conservative pair force and the
//! Ornstein-Uhlenbeck pair update together, exactly per pair. Their cost and orders are
//! claimed in the [`registry`](crate::registry). As gamma grows the exact pair relaxation swamps the
//! conservative force and these schemes degrade.

use dpd_core::Scheme;
use dpd_macros::dpd_scheme;

/// SAS (DPD-Trotter), written `TAT` here (S names compositions in the scheme language).
///
/// ```text
/// T>(1/2) A(1) T<(1/2)
/// ```
///
/// Each T sweep evaluates its pair forces inline, so each counts as a force evaluation. Source:
/// T. Serrano, G. De Fabritiis, P. Español and P. V. Coveney, "A stochastic Trotter
/// integration scheme for dissipative particle dynamics", Math. Comput. Simul. 72, 190 (2006).
pub fn sas() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!("TAT", name = "sas")
}

/// ASA: the other symmetric arrangement of the same pieces.
///
/// ```text
/// A(1/2) T(1) A(1/2)
/// ```
///
/// Its invariant-measure order is lower than SAS's: a pair generator `B_k + O_k` of T does not
/// annihilate the Gibbs density on its own (only their sum with A does), and a single sweep
/// visits the pairs in one order, which SAS mirrors and ASA does not. Source: the other ordering of Serrano et al.
/// (2006).
pub fn asa() -> impl Scheme + Copy + Send + Sync + 'static {
    dpd_scheme!("ATA", name = "asa")
}
