//! The `Scheme` trait, the run-time interpreter of a stage sequence, and the guarded step
//! that detects blow-ups.

use crate::boundary::LeesEdwards;
use crate::error::BlowUp;
use crate::flow::{bbk, drift, full_force, kick, ou, trotter};
use crate::observe::ImpulseVirial;
use crate::system::{on_all_threads, System};
use crate::{Tensor, Vec3};
use dpd_ir::{Diagnostic, Flow, Options, Program, Stage};
use rayon::prelude::*;

/// An integrator: one step of length `sys.dt()`.
///
/// Implemented by the zero-sized types that `dpd_scheme!` generates (straight-line calls of the
/// sub-flows), by [`DynScheme`] (the same stages walked at run time) and by hand-written
/// methods. Use [`System::advance`] to step with blow-up detection.
///
/// A hand-written step that keeps per-particle data across sub-flow calls must key it by
/// [`System::ids`]: any sub-flow that evaluates pairs may rebuild the neighbour list, which
/// re-sorts the particles.
pub trait Scheme {
    /// Short name used in reports and errors.
    fn name(&self) -> &str;

    /// Advance `sys` by one step, without checks and without incrementing the step counter
    /// (random numbers are keyed by `sys.step()`).
    fn step(&self, sys: &mut System);

    /// The flattened stage sequence, where the scheme is a splitting written in the scheme
    /// language: coefficients, evaluations per step, symmetry and order analysis.
    fn program(&self) -> Option<&Program> {
        None
    }
}

impl<S: Scheme + ?Sized> Scheme for &S {
    fn name(&self) -> &str {
        (**self).name()
    }
    fn step(&self, sys: &mut System) {
        (**self).step(sys)
    }
    fn program(&self) -> Option<&Program> {
        (**self).program()
    }
}

impl<S: Scheme + ?Sized> Scheme for Box<S> {
    fn name(&self) -> &str {
        (**self).name()
    }
    fn step(&self, sys: &mut System) {
        (**self).step(sys)
    }
    fn program(&self) -> Option<&Program> {
        (**self).program()
    }
}

/// Apply one stage: the sub-flow with step length `coeff * dt`. The macro emits the same call
/// with the same `f64` constants, so both paths give bitwise identical trajectories.
#[inline(always)]
pub fn apply_stage(sys: &mut System, stage: &Stage) {
    let h = stage.coeff.value * sys.dt;
    match stage.flow {
        Flow::A => drift(sys, h),
        Flow::B => kick(sys, h),
        Flow::O => ou(sys, h, stage.stream, stage.order),
        Flow::Bbk => bbk(sys, h, stage.stream, stage.order),
        Flow::T => trotter(sys, h, stage.stream, stage.order),
        Flow::F => full_force(sys, h, stage.stream),
    }
}

/// A scheme compiled from a string at run time and walked stage by stage (schemes given on the
/// command line). Same parser, same program and same sub-flow calls as `dpd_scheme!`, hence
/// bitwise the same trajectory.
#[derive(Clone, Debug)]
pub struct DynScheme {
    name: String,
    program: Program,
}

impl DynScheme {
    /// Compile `source` in the scheme language; errors carry byte spans into `source`.
    pub fn compile(
        name: impl Into<String>,
        source: &str,
        options: &Options,
    ) -> Result<Self, Vec<Diagnostic>> {
        Ok(DynScheme {
            name: name.into(),
            program: dpd_ir::compile_with(source, options)?,
        })
    }

    /// A scheme running a program the language produced.
    pub fn from_program(name: impl Into<String>, program: Program) -> Self {
        DynScheme {
            name: name.into(),
            program,
        }
    }
}

impl Scheme for DynScheme {
    fn name(&self) -> &str {
        &self.name
    }
    fn step(&self, sys: &mut System) {
        for stage in &self.program.stages {
            apply_stage(sys, stage);
        }
    }
    fn program(&self) -> Option<&Program> {
        Some(&self.program)
    }
}

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
}

impl System {
    /// Take `steps` steps of `scheme`, each guarded: a step that produces a non-finite position
    /// or momentum, or that may have moved a particle by more than half the shortest box edge
    /// (the sum over its drifts of the largest drift length exceeds it), is undone and
    /// reported; the system is then in the state after the last good step.
    pub fn advance<S: Scheme + ?Sized>(&mut self, scheme: &S, steps: u64) -> Result<(), BlowUp> {
        let mut backup = std::mem::take(&mut self.backup);
        let result = (0..steps).try_for_each(|_| self.guarded_step(scheme, &mut backup));
        self.backup = backup;
        result
    }

    fn guarded_step<S: Scheme + ?Sized>(
        &mut self,
        scheme: &S,
        backup: &mut Backup,
    ) -> Result<(), BlowUp> {
        copy(&mut backup.q, &self.q);
        copy(&mut backup.p, &self.p);
        copy(&mut backup.id, &self.id);
        backup.full_valid = self.full_valid;
        if self.full_valid {
            copy(&mut backup.full, &self.full);
        }
        backup.full_virial = self.full_virial;
        backup.shear = self.shear;
        backup.impulses = self.impulses;
        self.drift_bound = 0.0;
        scheme.step(self);
        let reason = if !self.drift_bound.is_finite() || !finite(&self.q) || !finite(&self.p) {
            Some("a position or momentum became non-finite".to_string())
        } else if self.drift_bound > 0.5 * self.bx.min_length() {
            Some(format!(
                "a particle may have moved {:.3e} in one step, more than half the box edge {}",
                self.drift_bound,
                self.bx.min_length()
            ))
        } else {
            None
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
                    self.full_valid = true;
                }
                self.full_virial = backup.full_virial;
                self.shear = backup.shear;
                self.impulses = backup.impulses;
                Err(BlowUp {
                    step: self.step,
                    scheme: scheme.name().to_string(),
                    reason,
                })
            }
        }
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

/// Whether every component of every vector is finite.
fn finite(v: &[Vec3]) -> bool {
    let ok = |v: &Vec3| v.iter().all(|x| x.is_finite());
    if on_all_threads(v.len()) {
        v.par_iter().with_min_len(4096).all(ok)
    } else {
        v.iter().all(ok)
    }
}
