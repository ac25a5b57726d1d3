//! Stability at the extremes: short runs of every scheme over a matrix of friction, mass and
//! time step on a small box, each classified as completed (with its temperature errors),
//! blown up (as detected by the guarded step), or completed with insane temperatures.
//!
//! Scene: the standard fluid (a = 25, k_B T = 1, r_c = 1, s = 2, density 3) in a small cubic
//! box. All runs start from one configuration equilibrated with ABOBA (m = 1, gamma = 4.5,
//! dt = 0.05, 10 time units): the Gibbs distribution of positions does not depend on mass or
//! friction, so every run starts in equilibrium, with Maxwell momenta for its mass, and the
//! temperature errors measure what the scheme does to an equilibrium state. Temperatures are
//! averaged over the second half of the run, at the end of full steps. Schemes with
//! Lowe-Andersen collisions collide at the fixed [`COLLISION_RATE`], adaptive schemes (PAdL,
//! PNHL) have the fixed [`THERMOSTAT_MASS`], PNHL's the [`THERMOSTAT_FRICTION`].
//!
//! The blow-up guard of `System::advance` also trips when a particle may have moved more than
//! half the box edge between two checks of the neighbour list; in a small box with light
//! particles (thermal speed `sqrt(k_B T / m)`, 32 at m = 1e-3) that happens at large dt even
//! for a scheme that would otherwise be stable, and is reported as a blow-up with that reason.

use dpd_core::error::{AdvanceError, ParamError};
use dpd_core::init::{cubic_box, maxwell_momenta, uniform_positions};
use dpd_core::observe::{thermo, ThermoAverages};
use dpd_core::params::ParamsBuilder;
use dpd_core::reference::Aboba;
use dpd_core::{Params, PeriodicBox, Scheme, System, Vec3};
use dpd_ir::Flow;
use rayon::prelude::*;
use serde::Serialize;

use crate::registry::Entry;

/// The collision frequency of schemes with L (Lowe-Andersen collisions), whatever the matrix's
/// friction: their thermostat does not use it. 0.54 relaxes pairs at the mean rate of O's at
/// gamma = 4.5 (docs/design-search.md).
pub const COLLISION_RATE: f64 = 0.54;

/// The thermostat mass of schemes with Oa and Xi (PAdL), whatever the matrix's friction:
/// 10 gamma^2 at gamma = 4.5, xi = 1 +- 0.07 (docs/design-search.md).
pub const THERMOSTAT_MASS: f64 = 202.5;

/// The Langevin friction of xi in schemes with On (PNHL), per unit time: xi's
/// Ornstein-Uhlenbeck part relaxes over one time unit.
pub const THERMOSTAT_FRICTION: f64 = 1.0;

/// `params` with the [`THERMOSTAT_FRICTION`] when `scheme` has an On stage (PNHL), without it
/// otherwise (a scheme with Oa refuses it: PAdL's xi centres on 1).
pub fn with_thermostat_friction(params: ParamsBuilder, scheme: &dyn Scheme) -> ParamsBuilder {
    let pnhl = (scheme.program()).is_some_and(|p| p.stages.iter().any(|s| s.flow == Flow::On));
    match pnhl {
        true => params.thermostat_friction(THERMOSTAT_FRICTION),
        false => params,
    }
}

/// A completed run is sane when both mean temperatures are within this factor of k_B T: a
/// run at twice or half the target temperature is not a usable simulation, even if nothing
/// overflowed.
pub const SANE_FACTOR: f64 = 2.0;

/// Number of thermodynamic samples taken over the second half of a run (at most one per
/// step).
const SAMPLES: u64 = 50;

/// Steps of the equilibration run that prepares the common starting configuration.
const EQUILIBRATION_STEPS: u64 = 200;

/// The combinations to run and the box to run them in.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Matrix {
    pub gammas: Vec<f64>,
    pub masses: Vec<f64>,
    pub dts: Vec<f64>,
    /// Steps per run.
    pub steps: u64,
    pub particles: usize,
    pub density: f64,
    pub seed: u64,
}

impl Matrix {
    /// The matrix of issue 5: gamma in {0, 4.5, 450, 1e4}, mass in {1e-3, 1, 1e3}, dt in
    /// {1e-4, 1e-3, 1e-2, 0.1, 0.5}; 400 steps of N = 150 at density 3 (box edge 3.68).
    pub fn full() -> Matrix {
        Matrix {
            gammas: vec![0.0, 4.5, 450.0, 1e4],
            masses: vec![1e-3, 1.0, 1e3],
            dts: vec![1e-4, 1e-3, 1e-2, 0.1, 0.5],
            steps: 400,
            particles: 150,
            density: 3.0,
            seed: 1,
        }
    }

    /// The corners of the full matrix (gamma in {0, 1e4}, mass in {1e-3, 1e3}, dt in
    /// {1e-4, 0.5}) plus the standard point (gamma = 4.5, m = 1, dt = 0.01), 40 steps of
    /// N = 100: a quick check that nothing panics or returns NaN.
    pub fn reduced() -> Matrix {
        Matrix {
            gammas: vec![0.0, 4.5, 1e4],
            masses: vec![1e-3, 1.0, 1e3],
            dts: vec![1e-4, 1e-2, 0.5],
            steps: 40,
            particles: 100,
            density: 3.0,
            seed: 1,
        }
    }

    /// Every (gamma, mass, dt), gamma slowest.
    pub fn cases(&self) -> Vec<(f64, f64, f64)> {
        let mut cases = Vec::new();
        for &gamma in &self.gammas {
            for &mass in &self.masses {
                for &dt in &self.dts {
                    cases.push((gamma, mass, dt));
                }
            }
        }
        cases
    }

    /// Checks every value, so that a run can fail only by what the scheme does.
    pub fn validate(&self) -> Result<(), ParamError> {
        let lists = [
            ("gamma", &self.gammas),
            ("mass", &self.masses),
            ("dt", &self.dts),
        ];
        for (field, list) in lists {
            if list.is_empty() {
                return Err(ParamError::new(field, "[]", "needs at least one value"));
            }
        }
        for &gamma in &self.gammas {
            Params::builder().gamma(gamma).build()?;
        }
        for (field, list) in [("mass", &self.masses), ("dt", &self.dts)] {
            if let Some(&bad) = list.iter().find(|x| !(x.is_finite() && **x > 0.0)) {
                return Err(ParamError::new(field, bad, "must be finite and > 0"));
            }
        }
        if self.steps < 2 {
            return Err(ParamError::new(
                "steps",
                self.steps,
                "must be at least 2 (temperatures are averaged over the second half)",
            ));
        }
        let bx = cubic_box(self.particles, self.density)?;
        // The builder checks the box edge against 2 (r_c + skin) and the particle count.
        System::builder(
            Params::builder().build()?,
            bx,
            uniform_positions(&bx, self.particles, self.seed),
        )
        .build()?;
        Ok(())
    }
}

/// What one run did.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "status", rename_all = "snake_case")]
pub enum Outcome {
    /// All steps completed with sane mean temperatures; errors are `T / (k_B T) - 1`.
    Completed {
        kinetic_temperature: f64,
        configurational_temperature: f64,
        kinetic_error: f64,
        configurational_error: f64,
    },
    /// The guarded step detected a blow-up at `step` and stopped.
    BlowUp { step: u64, reason: String },
    /// All steps completed, but a mean temperature is non-finite (`None`) or off by more than
    /// [`SANE_FACTOR`].
    Insane {
        kinetic_temperature: Option<f64>,
        configurational_temperature: Option<f64>,
        reason: String,
    },
}

/// One scheme at one combination.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Record {
    pub scheme: &'static str,
    pub gamma: f64,
    pub mass: f64,
    pub dt: f64,
    pub outcome: Outcome,
}

/// Runs every scheme of `schemes` at every combination of `matrix`, in parallel; records in
/// the order scheme, then [`Matrix::cases`].
pub fn run(matrix: &Matrix, schemes: &[&'static Entry]) -> Result<Vec<Record>, ParamError> {
    matrix.validate()?;
    let (bx, start) = equilibrated_start(matrix)?;
    let jobs: Vec<(&'static Entry, (f64, f64, f64))> = schemes
        .iter()
        .flat_map(|&e| matrix.cases().into_iter().map(move |c| (e, c)))
        .collect();
    jobs.into_par_iter()
        .map(|(entry, (gamma, mass, dt))| {
            let scheme = entry.scheme();
            let outcome = run_one(&*scheme, matrix, bx, &start, gamma, mass, dt)?;
            Ok(Record {
                scheme: entry.name,
                gamma,
                mass,
                dt,
                outcome,
            })
        })
        .collect()
}

/// The box and a configuration equilibrated at the standard state.
fn equilibrated_start(matrix: &Matrix) -> Result<(PeriodicBox, Vec<Vec3>), ParamError> {
    let bx = cubic_box(matrix.particles, matrix.density)?;
    let params = Params::builder().build()?;
    let masses = vec![1.0; matrix.particles];
    let mut sys = System::builder(
        params.clone(),
        bx,
        uniform_positions(&bx, matrix.particles, matrix.seed),
    )
    .momenta(maxwell_momenta(&masses, params.kbt(), matrix.seed))
    .dt(0.05)
    .seed(matrix.seed)
    .build()?;
    sys.advance(&Aboba, EQUILIBRATION_STEPS).map_err(|e| {
        ParamError::new(
            "equilibration",
            e.to_string(),
            "the standard box must equilibrate with ABOBA at dt = 0.05",
        )
    })?;
    Ok((bx, sys.positions().to_vec()))
}

fn run_one(
    scheme: &dyn Scheme,
    matrix: &Matrix,
    bx: PeriodicBox,
    start: &[Vec3],
    gamma: f64,
    mass: f64,
    dt: f64,
) -> Result<Outcome, ParamError> {
    let params = (Params::builder().gamma(gamma))
        .collision_rate(COLLISION_RATE)
        .thermostat_mass(THERMOSTAT_MASS);
    let params = with_thermostat_friction(params, scheme).build()?;
    let kbt = params.kbt();
    let masses = vec![mass; start.len()];
    let mut sys = System::builder(params, bx, start.to_vec())
        .momenta(maxwell_momenta(&masses, kbt, matrix.seed))
        .masses(masses)
        .dt(dt)
        .seed(matrix.seed)
        .build()?;
    let mut averages = ThermoAverages::new(matrix.steps, 0.5)?;
    let stride = (matrix.steps / 2 / SAMPLES).max(1);
    while sys.step() < matrix.steps {
        let k = stride.min(matrix.steps - sys.step());
        match sys.advance(scheme, k) {
            Ok(()) => {}
            Err(AdvanceError::BlowUp(blow_up)) => {
                return Ok(Outcome::BlowUp {
                    step: blow_up.step,
                    reason: blow_up.reason,
                })
            }
            Err(AdvanceError::Scheme(e)) => return Err(e),
        }
        if averages.wants(sys.step()) {
            averages.record(&thermo(&mut sys));
        }
    }
    let summary = averages.summary();
    Ok(classify(
        summary.kinetic_temperature,
        summary.configurational_temperature,
        kbt,
    ))
}

/// Completed or insane, by [`SANE_FACTOR`].
fn classify(kinetic: f64, configurational: f64, kbt: f64) -> Outcome {
    let finite = |t: f64| Some(t).filter(|t| t.is_finite());
    let sane = |t: f64| t.is_finite() && t >= kbt / SANE_FACTOR && t <= kbt * SANE_FACTOR;
    if sane(kinetic) && sane(configurational) {
        return Outcome::Completed {
            kinetic_temperature: kinetic,
            configurational_temperature: configurational,
            kinetic_error: kinetic / kbt - 1.0,
            configurational_error: configurational / kbt - 1.0,
        };
    }
    let describe = |name: &str, t: f64| {
        if t.is_finite() {
            format!("{name} = {t:.4e}")
        } else {
            format!("{name} is not finite")
        }
    };
    let bad: Vec<String> = [("T_K", kinetic), ("T_C", configurational)]
        .into_iter()
        .filter(|&(_, t)| !sane(t))
        .map(|(name, t)| describe(name, t))
        .collect();
    Outcome::Insane {
        kinetic_temperature: finite(kinetic),
        configurational_temperature: finite(configurational),
        reason: format!(
            "{} (sane: within a factor {SANE_FACTOR} of k_B T = {kbt})",
            bad.join(", ")
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classification_never_carries_nan() {
        let o = classify(f64::NAN, 1.0, 1.0);
        assert!(matches!(
            o,
            Outcome::Insane {
                kinetic_temperature: None,
                configurational_temperature: Some(_),
                ..
            }
        ));
        assert!(matches!(
            classify(1.01, 0.98, 1.0),
            Outcome::Completed { .. }
        ));
        let Outcome::Insane { reason, .. } = classify(1.0, 2.5, 1.0) else {
            panic!("T_C = 2.5 is insane")
        };
        assert!(reason.contains("T_C = 2.5"), "{reason}");
    }

    #[test]
    fn invalid_matrices_name_the_field() {
        let spoilt = |spoil: &dyn Fn(&mut Matrix)| {
            let mut m = Matrix::reduced();
            spoil(&mut m);
            m.validate().unwrap_err().field
        };
        assert_eq!(spoilt(&|m| m.gammas = vec![-1.0]), "gamma");
        assert_eq!(spoilt(&|m| m.masses = vec![0.0]), "mass");
        assert_eq!(spoilt(&|m| m.dts = vec![]), "dt");
        assert_eq!(spoilt(&|m| m.steps = 1), "steps");
        assert_eq!(spoilt(&|m| m.particles = 20), "box");
    }
}
