//! The `Scheme` trait, the run-time interpreter of a stage sequence, and the guarded step
//! that detects blow-ups.

use crate::error::BlowUp;
use crate::flow::{bbk, drift, full_force, kick, ou, trotter};
use crate::system::System;
use crate::Vec3;
use dpd_ir::{Flow, Stage};

/// An integrator: one step of length `sys.dt()`.
///
/// Implemented by the zero-sized types that `dpd_scheme!` generates (straight-line calls of the
/// sub-flows), by [`DynScheme`] (the same stages walked at run time) and by hand-written
/// methods. Use [`System::advance`] to step with blow-up detection.
pub trait Scheme {
    /// Short name used in reports and errors.
    fn name(&self) -> &str;

    /// Advance `sys` by one step, without checks and without incrementing the step counter
    /// (random numbers are keyed by `sys.step()`).
    fn step(&self, sys: &mut System);
}

impl<S: Scheme + ?Sized> Scheme for &S {
    fn name(&self) -> &str {
        (**self).name()
    }
    fn step(&self, sys: &mut System) {
        (**self).step(sys)
    }
}

impl<S: Scheme + ?Sized> Scheme for Box<S> {
    fn name(&self) -> &str {
        (**self).name()
    }
    fn step(&self, sys: &mut System) {
        (**self).step(sys)
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

/// A scheme whose stages are walked at run time (schemes given as strings on the command line).
#[derive(Clone, Debug)]
pub struct DynScheme {
    name: String,
    stages: Vec<Stage>,
}

impl DynScheme {
    /// A scheme applying `stages` in order. The stages are trusted to be valid, as produced by
    /// the scheme language.
    pub fn from_stages(name: impl Into<String>, stages: Vec<Stage>) -> Self {
        DynScheme {
            name: name.into(),
            stages,
        }
    }

    pub fn stages(&self) -> &[Stage] {
        &self.stages
    }
}

impl Scheme for DynScheme {
    fn name(&self) -> &str {
        &self.name
    }
    fn step(&self, sys: &mut System) {
        for stage in &self.stages {
            apply_stage(sys, stage);
        }
    }
}

/// The state a failed step must not lose.
#[derive(Clone, Debug, Default)]
pub(crate) struct Backup {
    q: Vec<Vec3>,
    p: Vec<Vec3>,
    full: Vec<Vec3>,
    full_valid: bool,
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
        backup.q.clone_from(&self.q);
        backup.p.clone_from(&self.p);
        backup.full_valid = self.full_valid;
        if self.full_valid {
            backup.full.clone_from(&self.full);
        }
        self.drift_bound = 0.0;
        scheme.step(self);
        let reason = if !self.drift_bound.is_finite()
            || !self
                .q
                .iter()
                .chain(&self.p)
                .all(|v| v.iter().all(|x| x.is_finite()))
        {
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
                self.positions_changed();
                if backup.full_valid {
                    std::mem::swap(&mut self.full, &mut backup.full);
                    self.full_valid = true;
                }
                Err(BlowUp {
                    step: self.step,
                    scheme: scheme.name().to_string(),
                    reason,
                })
            }
        }
    }
}
