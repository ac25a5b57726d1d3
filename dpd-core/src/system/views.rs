//! The state as the sub-flows ([`crate::flow`]) see it: each flow takes the view it needs
//! through one of these methods, and reports back what the caches and the guarded step must
//! know (moved positions, force evaluations; what it adds to a recording goes through
//! `records.rs`). No flow touches a cache or a counter directly.

use super::System;
use crate::boundary::{LeesEdwards, PeriodicBox};
use crate::pairs::{Noise, PairTable};
use crate::params::Params;
use crate::walls::Walls;
use crate::Vec3;

/// What a drift moves: the particles and the boundaries that wrap them.
pub(crate) struct Motion<'a> {
    pub(crate) bx: PeriodicBox,
    /// Lees-Edwards boundaries, whose offset the drift advances.
    pub(crate) shear: Option<&'a mut LeesEdwards>,
    pub(crate) walls: Option<Walls>,
    pub(crate) q: &'a mut [Vec3],
    pub(crate) p: &'a mut [Vec3],
    /// Inverse masses, 0 for frozen particles.
    pub(crate) inv_mass: &'a [f64],
    pub(crate) mass: &'a [f64],
}

/// What a pairwise sub-flow reads and writes: the pairs at the current positions, the momenta,
/// the per-particle data of the pair updates and the noise of one stream in the current step.
pub(crate) struct PairState<'a> {
    pub(crate) pairs: &'a PairTable,
    pub(crate) p: &'a mut [Vec3],
    pub(crate) inv_mass: &'a [f64],
    pub(crate) kind: &'a [u16],
    pub(crate) params: &'a Params,
    pub(crate) noise: Noise<'a>,
    /// External force on every mobile particle.
    pub(crate) body_force: Option<Vec3>,
}

impl System {
    /// The particles and boundaries for a drift; call [`System::moved`] after moving them.
    pub(crate) fn motion(&mut self) -> Motion<'_> {
        Motion {
            bx: self.bx,
            shear: self.shear.as_mut(),
            walls: self.walls.as_ref().map(|w| w.walls),
            q: &mut self.q,
            p: &mut self.p,
            inv_mass: &self.inv_mass,
            mass: &self.mass,
        }
    }

    /// The positions moved, by at most `largest_displacement` per particle (NaN if any
    /// position is NaN): the travel since the last check of the neighbour list grows by it,
    /// the guarded step's drift bound is at least that travel, and every cache tied to the
    /// positions is stale.
    pub(crate) fn moved(&mut self, largest_displacement: f64) {
        self.travel += largest_displacement;
        self.drift_bound = if self.travel.is_nan() || self.drift_bound.is_nan() {
            f64::NAN
        } else {
            self.drift_bound.max(self.travel)
        };
        self.positions_changed();
    }

    /// The momenta and the conservative forces at the current positions (evaluated if
    /// needed).
    pub(crate) fn momenta_and_conservative(&mut self) -> (&mut [Vec3], &[Vec3]) {
        self.ensure_conservative();
        (&mut self.p, &self.conservative)
    }

    /// The momenta and the full forces at the current positions (evaluated with the noise of
    /// `stream` if needed).
    pub(crate) fn momenta_and_full(&mut self, stream: u8) -> (&mut [Vec3], &[Vec3]) {
        self.ensure_full(stream);
        (&mut self.p, &self.full)
    }

    /// The state of a pairwise sub-flow with the noise of `stream` in the current step, the
    /// pair table evaluated if needed. Counts nothing: a flow that evaluates forces from the
    /// pairs calls [`System::count_force_evaluation`].
    pub(crate) fn pair_state(&mut self, stream: u8) -> PairState<'_> {
        self.ensure_sweep_pairs();
        PairState {
            pairs: &self.pairs,
            p: &mut self.p,
            inv_mass: &self.inv_mass,
            kind: &self.kind,
            params: &self.params,
            noise: Noise {
                seed: self.seed,
                step: self.step,
                stream,
                id: &self.id,
            },
            body_force: self.body_force,
        }
    }

    /// One more per-particle force evaluation (counted for [`System::counters`]).
    pub(crate) fn count_force_evaluation(&mut self) {
        self.counters.force_evaluations += 1;
    }

    /// Whether some pairs carry a velocity shift (`PairTable::shifts`): under shear or with walls.
    pub(crate) fn shifted_pairs(&self) -> bool {
        self.shear.is_some() || self.walls.is_some()
    }

    /// `p_i += h g` for every mobile particle, `g` the body force (nothing without one). The
    /// sub-flows that apply the conservative force (B, F, T) call it, so the body force is part
    /// of every letter that carries `F^C`, never of the cached forces.
    pub(crate) fn apply_body_force(&mut self, h: f64) {
        if let Some(g) = self.body_force {
            for (p, &im) in self.p.iter_mut().zip(&self.inv_mass) {
                if im > 0.0 {
                    *p += h * g;
                }
            }
        }
    }
}
