//! The `Scheme` trait, [`System::advance`] and the run-time interpreter of a stage sequence
//! (the guarded step that detects blow-ups is in `system/guard.rs`).

use crate::error::BlowUp;
use crate::flow::{bbk, drift, full_force, kick, ou, trotter};
use crate::system::System;
use dpd_ir::{Diagnostic, Flow, Options, Program, Stage};

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

impl System {
    /// Take `steps` steps of `scheme`, each guarded: a step that produces a non-finite position
    /// or momentum, or that may have moved a particle between two checks of the neighbour
    /// list by more than half the shortest box edge less the skin, is undone and reported; the
    /// system is then in the state after the last good step.
    pub fn advance<S: Scheme + ?Sized>(&mut self, scheme: &S, steps: u64) -> Result<(), BlowUp> {
        self.guarded_steps(steps, scheme.name(), |sys| scheme.step(sys))
    }
}

/// Apply one stage: the sub-flow with step length `coeff * dt`. The macro emits the same call
/// with the same `f64` constants, so both paths give bitwise identical trajectories.
#[inline(always)]
pub fn apply_stage(sys: &mut System, stage: &Stage) {
    let h = stage.coeff.value * sys.dt();
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
