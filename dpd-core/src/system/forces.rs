//! The force caches: conservative and full forces evaluated at most once per set of positions.

use super::System;
use crate::force::{self, Full, FullInputs};
use crate::pairs::{Excluding, Particles, Run};
use crate::stamp::Stamp;
use crate::{Tensor, Vec3};

impl System {
    pub(crate) fn ensure_conservative(&mut self) {
        if self.conservative_at.is_fresh(self.positions) {
            return;
        }
        if !self.fills_plainly() {
            self.ensure_pairs();
            let particles = Particles::new(&self.inv_mass, &self.kind, self.params.coefficients());
            force::conservative(&self.pairs, particles, &mut self.conservative);
        } else {
            // The forces of each run summed while the run is in cache, in the order of a pass
            // over the table: the same numbers.
            self.prepare_list();
            let out = force::zeroed(&mut self.conservative, self.kind.len());
            let particles = Particles::new(&self.inv_mass, &self.kind, self.params.coefficients());
            // A plain loop: through `Run::sweep` (AVX2-compiled, as the full forces are) ABOBA
            // ran 3 % more instructions.
            let each = |run: Run<Vec3, ()>| run.for_each(force::add_conservative);
            let (list, q, bx, params) = (&self.list, &self.q, &self.bx, &self.params);
            let excluding = Excluding::of(self.exclusions.as_ref(), &self.id);
            self.pairs
                .collect_then(list, q, bx, params, excluding, None, particles, out, each);
            self.pairs_filled();
        }
        self.conservative_at = Stamp::at(self.positions);
        self.counters.force_evaluations += 1;
    }

    /// The pairs at the current positions for a pair sweep. When the scheme kicks with the
    /// conservative forces after the sweep at the same positions (`O B[pair]`, set by
    /// [`System::advance`]) and the table is stale, it is filled while those forces are summed
    /// run by run, as a B would: one pass over the pairs instead of a fill and a pass over the
    /// table, the same numbers.
    pub(crate) fn ensure_sweep_pairs(&mut self) {
        if self.sweeps_fill_forces && self.fills_plainly() {
            self.ensure_conservative();
        }
        self.ensure_pairs();
    }

    /// Whether pair sweeps fill the pair table with the conservative forces
    /// ([`System::ensure_sweep_pairs`]).
    pub(crate) fn set_sweeps_fill_forces(&mut self, on: bool) {
        self.sweeps_fill_forces = on;
    }

    /// Full forces for an F stage: reused while positions are unchanged, otherwise evaluated
    /// at the current momenta with the noise of `stream` in the current step.
    pub(crate) fn ensure_full(&mut self, stream: u8) {
        if self.full_at.is_fresh(self.positions) {
            return;
        }
        if self.fills_plainly() {
            self.prepare_list();
            force::full_while_filling(self.full_inputs(stream));
            self.full_virial = None;
            self.pairs_filled();
        } else {
            self.ensure_pairs();
            self.full_virial = self.full_from_table(stream);
        }
        self.full_at = Stamp::at(self.positions);
        self.counters.force_evaluations += 1;
    }

    /// Whether a force evaluation may fill the pair table and apply the forces run by run
    /// ([`PairTable::collect_then`]): the table is stale, the box is periodic without walls,
    /// and no pair impulses are being recorded.
    fn fills_plainly(&self) -> bool {
        !self.pairs_at.is_fresh(self.positions)
            && self.shear.is_none()
            && self.walls.is_none()
            && self.impulses.is_none()
    }

    /// Full forces from the filled pair table; the pair virial of their dissipative and random
    /// parts when impulses are being recorded.
    fn full_from_table(&mut self, stream: u8) -> Option<Tensor> {
        match (self.shifted_pairs(), self.impulses.is_some()) {
            (false, false) => {
                force::full::<false, ()>(self.full_inputs(stream));
                None
            }
            (true, false) => {
                force::full::<true, ()>(self.full_inputs(stream));
                None
            }
            (false, true) => Some(force::full::<false, Tensor>(self.full_inputs(stream))),
            (true, true) => Some(force::full::<true, Tensor>(self.full_inputs(stream))),
        }
    }

    /// The system taken apart for a full-force evaluation with the noise of `stream` in the
    /// current step.
    fn full_inputs(&mut self, stream: u8) -> FullInputs<'_> {
        let System {
            ref mut pairs,
            ref list,
            ref q,
            ref bx,
            ref p,
            ref inv_mass,
            ref kind,
            ref id,
            ref exclusions,
            ref params,
            ref mut full,
            seed,
            step,
            dt,
            ..
        } = *self;
        let add = Full::new(params, dt);
        let noise = add.noise(seed, step, stream, id);
        FullInputs {
            pairs,
            list,
            q,
            bx,
            params,
            excluding: Excluding::of(exclusions.as_ref(), id),
            particles: Particles::new(inv_mass, kind, params.coefficients()).with_momenta(p),
            full,
            add,
            noise,
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::force::conservative;
    use crate::init::equilibrium_box;
    use crate::pairs::Particles;
    use crate::params::Params;
    use crate::reference::VelocityVerlet;

    /// Forces summed run by run while the table is filled are bit for bit those of a pass
    /// over the filled table, on one thread and on several (20 000 particles: above the size
    /// where scans and pair passes split).
    #[test]
    fn forces_summed_while_filling_equal_a_pass_over_the_table() {
        for threads in [1, 3] {
            crate::on_threads(threads, || {
                let params = Params::builder().build().unwrap();
                let mut sys = equilibrium_box(params, 20_000, 3.0, 7)
                    .unwrap()
                    .dt(0.04)
                    .skin(0.0)
                    .build()
                    .unwrap();
                sys.advance(&VelocityVerlet, 3).unwrap();
                sys.positions_changed();
                sys.ensure_conservative();
                let filled_c = sys.conservative.clone();
                sys.positions_changed();
                sys.ensure_full(1);
                let filled_f = sys.full.clone();
                let mut pass = Vec::new();
                let particles = Particles::new(&sys.inv_mass, &sys.kind, sys.params.coefficients());
                conservative(&sys.pairs, particles, &mut pass);
                assert_eq!(pass, filled_c, "conservative, {threads} threads");
                sys.full_from_table(1);
                assert_eq!(sys.full, filled_f, "full, {threads} threads");
                assert!(filled_f.iter().any(|f| f.norm() > 0.0));
            });
        }
    }
}
