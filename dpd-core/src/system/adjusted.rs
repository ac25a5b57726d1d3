//! The state of a Metropolis-adjusted part (`{ ... }` of the scheme language, the sub-flows
//! [`crate::flow::propose`] and [`crate::flow::accept`]): what `{` keeps for a rejection, the
//! potential energy of the current positions, and the count of accepted proposals.

use super::System;
use crate::stamp::Stamp;
use crate::Vec3;

/// The accept/reject tests of Metropolis-adjusted parts since the system was built (carried by
/// checkpoints).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Acceptance {
    /// Tests made (one per `}` per step).
    pub proposed: u64,
    /// Tests that kept the proposed state.
    pub accepted: u64,
}

impl Acceptance {
    /// The fraction of tests accepted, `None` before the first.
    pub fn rate(&self) -> Option<f64> {
        (self.proposed > 0).then(|| self.accepted as f64 / self.proposed as f64)
    }
}

/// What `{` keeps for a rejection at `}`.
#[derive(Clone, Debug, Default)]
pub(crate) struct Proposal {
    q: Vec<Vec3>,
    p: Vec<Vec3>,
    /// Particle ids in storage order at `{` (evaluating pairs may re-sort the particles).
    id: Vec<u32>,
    travel: f64,
    /// `H = K + U` at `{` (energy units).
    energy: f64,
    /// `U` at `{`.
    potential_at_start: f64,
    /// `U` at the positions of generation `potential_at`: the next `{` reuses what `}`
    /// evaluated.
    potential: f64,
    potential_at: Stamp,
}

impl System {
    /// The potential energy `U` at the current positions: pair energies summed over the pair
    /// table in its fixed order (the same on any thread count) plus the bonded energy; cached
    /// until the positions change. Fills the pair table if it is stale, as the next pair
    /// sweep or kick at these positions would.
    pub(crate) fn adjusted_potential(&mut self) -> f64 {
        if self.proposal.potential_at.is_fresh(self.positions) {
            return self.proposal.potential;
        }
        self.ensure_pairs();
        let pairs: f64 = self
            .pairs
            .sum_soft(&self.params, &self.kind, |soft, pair| soft.energy(pair.w));
        self.proposal.potential = pairs + self.bonded_energy();
        self.proposal.potential_at = Stamp::at(self.positions);
        self.proposal.potential
    }

    /// Keep the state for a rejection: positions, momenta, storage order and the travel since
    /// the last check of the neighbour list, with `H` and `U` at this state.
    pub(crate) fn keep_proposal_start(&mut self, energy: f64, potential: f64) {
        let kept = &mut self.proposal;
        kept.q.clone_from(&self.q);
        kept.p.clone_from(&self.p);
        kept.id.clone_from(&self.id);
        kept.travel = self.travel;
        kept.energy = energy;
        kept.potential_at_start = potential;
    }

    /// `H` kept at `{`.
    pub(crate) fn proposal_start_energy(&self) -> f64 {
        self.proposal.energy
    }

    /// Count the test at `}`; on rejection put back the state kept at `{` with every momentum
    /// negated (the caches of the proposed positions are stale; `U` is known again).
    pub(crate) fn settle_proposal(&mut self, accepted: bool) {
        self.acceptance.proposed += 1;
        if accepted {
            self.acceptance.accepted += 1;
            return;
        }
        std::mem::swap(&mut self.q, &mut self.proposal.q);
        std::mem::swap(&mut self.p, &mut self.proposal.p);
        for p in &mut self.p {
            *p = -*p;
        }
        let ids = std::mem::take(&mut self.proposal.id);
        self.restore_order(&ids);
        self.proposal.id = ids;
        self.positions_changed();
        self.travel = self.proposal.travel;
        self.proposal.potential = self.proposal.potential_at_start;
        self.proposal.potential_at = Stamp::at(self.positions);
    }

    /// The accept/reject tests so far.
    pub fn acceptance(&self) -> Acceptance {
        self.acceptance
    }
}
