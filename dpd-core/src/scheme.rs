//! The `Scheme` trait, [`System::advance`] and the run-time interpreter of a stage sequence
//! (the guarded step that detects blow-ups is in `system/guard.rs`).

use crate::error::{AdvanceError, ParamError};
use crate::flow::{
    accept, adaptive_ou, bbk, collide, drift, full_force, full_force_group, kick, kick_group, ou,
    propose, trotter, xi_update,
};
use crate::system::System;
use dpd_ir::{Diagnostic, Flow, ForceGroup, Options, Program, Stage};

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
    /// system is then in the state after the last good step. A scheme that cannot run on the
    /// system ([`System::check_scheme`]) is refused before the first step.
    pub fn advance<S: Scheme + ?Sized>(
        &mut self,
        scheme: &S,
        steps: u64,
    ) -> Result<(), AdvanceError> {
        self.check_scheme(scheme)?;
        self.set_sweeps_fill_forces(scheme.program().is_some_and(kicks_after_sweeps));
        Ok(self.guarded_steps(steps, scheme.name(), |sys| scheme.step(sys))?)
    }

    /// Whether `scheme` can run on this system: each force group its program names
    /// (`B[bond]`) must be one the system has ([`System::force_groups`]), and each group the
    /// system has must be applied by some stage (a scheme of `B[pair]` and `T` alone leaves the
    /// bonded forces out); a program with L needs a collision rate ([`crate::Params::collision_rate`]),
    /// one with Xi a thermostat mass ([`crate::Params::thermostat_mass`]), one with On a
    /// thermostat friction ([`crate::Params::thermostat_friction`], which one with Oa must not
    /// have); a Metropolis-adjusted
    /// program (`{...}`) an equilibrium scene (no shear, walls or body force).
    /// Hand-written schemes, without a program, are not checked.
    pub fn check_scheme<S: Scheme + ?Sized>(&self, scheme: &S) -> Result<(), ParamError> {
        let Some(program) = scheme.program() else {
            return Ok(());
        };
        let has = self.force_groups();
        let refuse = |why: String| Err(ParamError::new("scheme", scheme.name(), why));
        if let Some(&g) = program.named_groups().iter().find(|g| !has.contains(g)) {
            let name = dpd_ir::lang::letters::group_spelling(g);
            return refuse(format!(
                "it applies B[{name}], the {}, which this system does not have; write B (all forces) or B[pair]",
                group_forces(g)
            ));
        }
        if let Some(&g) = has.iter().find(|&&g| !program.applies(g)) {
            let name = dpd_ir::lang::letters::group_spelling(g);
            return refuse(format!(
                "it never applies the {} of this system; add a B[{name}] stage, or use B or F for all forces",
                group_forces(g)
            ));
        }
        // Letters that read a parameter only they use: (letter, parameter set, field, why).
        let needs = [
            (
                Flow::L,
                self.params().collision_rate().is_some(),
                "collision_rate",
                "L (Lowe-Andersen collisions), which needs the collision frequency Gamma: set collision_rate to a finite value > 0 (per unit time)",
            ),
            (
                Flow::Xi,
                self.params().thermostat_mass().is_some(),
                "thermostat_mass",
                "Xi (the adaptive friction of PAdL and PNHL), which needs the thermostat mass mu: set thermostat_mass to a finite value > 0 (energy units; xi fluctuates around 1, PNHL around 0, with variance kbt / mu)",
            ),
            (
                Flow::On,
                self.params().thermostat_friction().is_some(),
                "thermostat_friction",
                "On (PNHL's pair sweep without noise), which needs the Langevin friction gamma_xi of xi, the only noise of the scheme: set thermostat_friction to a finite value > 0 (per unit time)",
            ),
        ];
        for (flow, set, field, why) in needs {
            if !set && program.stages.iter().any(|s| s.flow == flow) {
                let message = format!("scheme {} has {why}", scheme.name());
                return Err(ParamError::new(field, "unset", message));
            }
        }
        if let Some(gamma_xi) = self.params().thermostat_friction() {
            if program.stages.iter().any(|s| s.flow == Flow::Oa) {
                return Err(ParamError::new(
                    "thermostat_friction",
                    gamma_xi,
                    format!(
                        "scheme {} has Oa (PAdL), whose xi centres on 1: the Langevin dynamics of xi around 0 is PNHL's, for schemes with On (unset thermostat_friction)",
                        scheme.name()
                    ),
                ));
            }
        }
        // The accept/reject tests the energy of a Hamiltonian: not defined with a sliding
        // boundary (work done on the box), walls (reflections and frozen particles) or a body
        // force (no potential in a periodic box).
        let scene = [
            ("shear_rate", self.shear().is_some()),
            ("walls", self.walls().is_some()),
            ("body_force", self.body_force().is_some()),
        ];
        if let Some((key, _)) = scene
            .iter()
            .find(|(_, set)| *set)
            .filter(|_| program.is_adjusted())
        {
            return Err(ParamError::new(
                *key,
                "set",
                format!(
                    "scheme {} is Metropolis-adjusted ({{...}}), whose accept/reject needs the energy of an equilibrium system: a scene without shear, walls or body force",
                    scheme.name()
                ),
            ));
        }
        Ok(())
    }
}

/// Whether some pair sweep of `program` (a stage other than A, B and F) is followed, before
/// any drift or full-force kick, by a kick with the conservative pair forces (B or B[pair]),
/// reading the stages cyclically: MTS's `... O B[pair]`. Such a program's sweeps fill the pair
/// table with those forces ([`System::ensure_sweep_pairs`]).
fn kicks_after_sweeps(program: &Program) -> bool {
    let stages = &program.stages;
    let n = stages.len();
    (0..n).any(|s| {
        !matches!(
            stages[s].flow,
            Flow::A | Flow::B | Flow::F | Flow::Propose | Flow::Accept
        ) && (1..n)
            .map(|k| &stages[(s + k) % n])
            .find(|t| {
                matches!(t.flow, Flow::A | Flow::F)
                    || (t.flow == Flow::B && t.group != Some(ForceGroup::Bond))
            })
            .is_some_and(|t| t.flow == Flow::B)
    })
}

/// What the forces of `group` are, for messages.
fn group_forces(group: ForceGroup) -> &'static str {
    match group {
        ForceGroup::Pair => "pair forces",
        ForceGroup::Bond => "bonded forces (bonds and angles)",
    }
}

/// Apply one stage: the sub-flow with step length `coeff * dt`. The macro emits the same call
/// with the same `f64` constants, so both paths give bitwise identical trajectories.
#[inline(always)]
pub fn apply_stage(sys: &mut System, stage: &Stage) {
    let h = stage.coeff.value * sys.dt();
    match (stage.flow, stage.group) {
        (Flow::A, _) => drift(sys, h),
        (Flow::B, None) => kick(sys, h),
        (Flow::B, Some(group)) => kick_group(sys, h, group),
        (Flow::O, _) => ou(sys, h, stage.stream, stage.order),
        (Flow::Bbk, _) => bbk(sys, h, stage.stream, stage.order),
        (Flow::T, _) => trotter(sys, h, stage.stream, stage.order),
        (Flow::F, None) => full_force(sys, h, stage.stream),
        (Flow::F, Some(group)) => full_force_group(sys, h, stage.stream, group),
        (Flow::L, _) => collide(sys, h, stage.stream, stage.order),
        (Flow::Oa, _) => adaptive_ou(sys, h, stage.stream, stage.order, true),
        (Flow::On, _) => adaptive_ou(sys, h, stage.stream, stage.order, false),
        (Flow::Xi, _) => xi_update(sys, h, stage.stream),
        (Flow::Propose, _) => propose(sys),
        (Flow::Accept, _) => accept(sys, stage.stream),
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A sweep fills the pair forces when a B or B[pair] follows it before any drift or F (B[bond]
    /// stages and other sweeps in between do not count), the stages read cyclically: the next
    /// step's first stages follow the last.
    #[test]
    fn sweeps_fill_the_pair_forces_when_a_pair_kick_follows_before_a_drift() {
        let kicks =
            |s: &str| kicks_after_sweeps(&dpd_ir::compile_with(s, &Options::default()).unwrap());
        assert!(kicks(
            "B[pair](1/2) (B[bond](1/8) A(1/4) B[bond](1/8))^4 O B[pair](1/2)"
        ));
        assert!(kicks("A(1/2) B(1/2) O B(1/2) A(1/2)"));
        assert!(kicks("B A O(1/2) O(1/2)"));
        assert!(kicks("O B[bond](1/2) B[pair] A B[bond](1/2)"));
        assert!(!kicks("B(1/2) A(1/2) O A(1/2) B(1/2)"));
        assert!(!kicks("O B[bond](1/2) A B[pair] B[bond](1/2)"));
        assert!(!kicks("F(1/2) A F(1/2)"));
    }
}
