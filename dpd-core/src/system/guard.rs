//! The guarded step: a step that blows up is undone, and the state before it is kept
//! ([`System::advance`] runs the steps of a scheme through it).

use super::{ImpulseVirial, System};
use crate::avx2::with_avx2;
use crate::boundary::LeesEdwards;
use crate::error::BlowUp;
use crate::parallel::on_all_threads;
use crate::stamp::Stamp;
use crate::{components, Tensor, Vec3};
use rayon::prelude::*;

/// The state a failed step must not lose.
#[derive(Clone, Debug, Default)]
pub(crate) struct Backup {
    q: Vec<Vec3>,
    /// Particle ids in storage order before the step (a step may re-sort the particles).
    id: Vec<u32>,
    p: Vec<Vec3>,
    full: Vec<Vec3>,
    full_valid: bool,
    full_virial: Option<Tensor>,
    shear: Option<LeesEdwards>,
    impulses: Option<ImpulseVirial>,
    heat: Option<f64>,
    xi: f64,
    acceptance: super::Acceptance,
    travel: f64,
}

impl System {
    /// Take `steps` steps with `step`, each guarded: a step that produces a non-finite
    /// position or momentum, that evaluates the bonded forces with a bond beyond its reach (a
    /// FENE bond at or past `R0`; the error names the bond and both ids), or that may have moved a particle between two checks of the
    /// neighbour list by more than half the shortest box edge less the skin (the sum of the
    /// largest drift lengths since the last check exceeds it: with a skin, the list's
    /// displacement test could no longer tell that move from one to another image; without
    /// one, such a move between two force evaluations is taken as a blow-up), is undone and
    /// reported as a blow-up of `scheme`; the system is then in the state after the last
    /// good step. A blow-up of a system with bonds that found no bond past its reach names
    /// the particle with the largest bonded force of the step's last evaluation, and its
    /// bonds.
    pub(crate) fn guarded_steps(
        &mut self,
        steps: u64,
        scheme: &str,
        mut step: impl FnMut(&mut System),
    ) -> Result<(), BlowUp> {
        let mut backup = std::mem::take(&mut self.backup);
        let result = (0..steps).try_for_each(|_| self.guarded_step(scheme, &mut step, &mut backup));
        self.backup = backup;
        result
    }

    fn guarded_step(
        &mut self,
        scheme: &str,
        step: &mut impl FnMut(&mut System),
        backup: &mut Backup,
    ) -> Result<(), BlowUp> {
        copy(&mut backup.q, &self.q);
        copy(&mut backup.p, &self.p);
        copy(&mut backup.id, &self.id);
        backup.full_valid = self.full_at.is_fresh(self.positions);
        if backup.full_valid {
            copy(&mut backup.full, &self.full);
        }
        backup.full_virial = self.full_virial;
        backup.shear = self.shear;
        backup.impulses = self.impulses;
        backup.heat = self.heat;
        backup.xi = self.xi;
        backup.acceptance = self.acceptance;
        backup.travel = self.travel;
        self.drift_bound = 0.0;
        self.overstretch = None;
        step(self);
        // An overstretched bond names itself; a step that went wrong otherwise names the
        // largest bonded force, if any, as a likely cause.
        let reason = match self.overstretch.take() {
            Some(o) => Some(self.overstretch_reason(o)),
            None => self
                .motion_failure()
                .map(|why| why + &self.largest_bonded_force_note()),
        };
        match reason {
            None => {
                self.step += 1;
                Ok(())
            }
            Some(reason) => {
                std::mem::swap(&mut self.q, &mut backup.q);
                std::mem::swap(&mut self.p, &mut backup.p);
                self.restore_order(&backup.id);
                self.positions_changed();
                if backup.full_valid {
                    std::mem::swap(&mut self.full, &mut backup.full);
                    self.full_at = Stamp::at(self.positions);
                }
                self.full_virial = backup.full_virial;
                self.shear = backup.shear;
                self.impulses = backup.impulses;
                self.heat = backup.heat;
                self.xi = backup.xi;
                self.acceptance = backup.acceptance;
                self.travel = backup.travel;
                Err(BlowUp {
                    step: self.step,
                    scheme: scheme.to_string(),
                    reason,
                })
            }
        }
    }

    /// Why a step's motion cannot be kept, if it cannot: a position or momentum that is not
    /// finite, or a particle that may have moved beyond the neighbour list's reach.
    fn motion_failure(&self) -> Option<String> {
        let (edge, skin) = (self.bx.min_length(), self.list.skin());
        if !self.drift_bound.is_finite() || !finite(&self.q) || !finite(&self.p) {
            Some("a position or momentum became non-finite".to_string())
        } else if self.drift_bound > 0.5 * (edge - skin) {
            Some(format!(
                "a particle may have moved {:.3e} between two checks of the neighbour list, \
                 more than half the box edge {edge} less the skin {skin}",
                self.drift_bound,
            ))
        } else {
            None
        }
    }

    /// The largest drift length the step under way has summed since the neighbour list last
    /// checked the positions (the bound the guarded step tests).
    #[cfg(test)]
    pub(crate) fn drift_bound(&self) -> f64 {
        self.drift_bound
    }
}

/// `to <- from`, on all threads for large systems.
fn copy<T: Copy + Send + Sync>(to: &mut Vec<T>, from: &[T]) {
    if on_all_threads(from.len()) {
        to.resize(from.len(), from[0]);
        to.par_chunks_mut(4096)
            .zip(from.par_chunks(4096))
            .for_each(|(t, f)| t.copy_from_slice(f));
    } else {
        to.clear();
        to.extend_from_slice(from);
    }
}

/// Whether every component of every vector is finite: one test per component without a branch,
/// which the compiler vectorises (with AVX2 where the CPU has it).
fn finite(v: &[Vec3]) -> bool {
    let ok = |x: &[f64]| with_avx2(|| !x.iter().fold(false, |bad, x| bad | !x.is_finite()));
    let x = components(v);
    if on_all_threads(v.len()) {
        x.par_chunks(3 * 4096).all(ok)
    } else {
        ok(x)
    }
}
