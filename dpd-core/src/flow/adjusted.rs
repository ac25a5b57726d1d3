//! The braces of a Metropolis-adjusted part, `{ ... }` (generalised hybrid Monte Carlo):
//! [`propose`] at `{` keeps the state and `H = K + U`, [`accept`] at `}` keeps the state the
//! A/B word reached with probability `min(1, exp(-Delta H / k_B T))`, else restores the kept
//! one with its momenta negated. The language admits only a symmetric A/B word inside (a
//! reversible, volume-preserving map) and only O, Ob and L outside, so the step leaves the
//! Gibbs measure `exp(-H / k_B T)` exactly invariant at any dt.
//!
//! `U` is the pair potential summed over the pair table plus the bonded energy: one pass over
//! the table at `}` (none at `{`, which reuses it, nor a force evaluation). A rejection costs
//! the pair fill and force evaluation of the restored positions, done by the stages after it.

use crate::rng::PairRng;
use crate::system::System;
use rand_core::RngCore;

/// `{`: keep the state and its energy `H = K + U` for the test at `}`.
#[inline]
pub fn propose(sys: &mut System) {
    let potential = sys.adjusted_potential();
    sys.keep_proposal_start(sys.kinetic_energy() + potential, potential);
}

/// The Philox stream of the accept/reject tests and of Xi's noise (PNHL): the sweeps'
/// streams are numbered from 0 and end below it (the language allows at most 255 of them per
/// step).
pub(super) const APART_STREAM: u8 = u8::MAX;

/// `}`: the Metropolis test of the state reached since `{`, on a uniform `U` drawn under the
/// system's seed from the stream of this step's tests, keyed as the pair `(part, part)` (which
/// no pair of particles is) for the `part`-th adjusted part of the step: kept if `U < exp(-Delta H / k_B T)`, else the state of `{` with its momenta
/// negated. A non-finite `Delta H` is a blow-up, not a rejection: the state is kept for the
/// guarded step to report, as for any other scheme.
#[inline]
pub fn accept(sys: &mut System, part: u8) {
    let energy = sys.kinetic_energy() + sys.adjusted_potential();
    let change = energy - sys.proposal_start_energy();
    let part = u32::from(part);
    let mut rng = PairRng::new(sys.seed(), sys.step(), APART_STREAM, part, part);
    let uniform = (rng.next_u64() >> 11) as f64 * f64::EPSILON / 2.0;
    let accepted = !change.is_finite() || uniform < (-change / sys.params().kbt()).exp();
    sys.settle_proposal(accepted);
}
