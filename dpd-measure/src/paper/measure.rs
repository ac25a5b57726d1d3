//! The runs of a paper item and the quantities read from them, each with its standard error.

use super::item::Item;
use crate::aggregate::Aggregate;
use crate::batch::{distinct, Batch};
use crate::critical::{critical_dt, Critical};
use crate::result::Job;
use crate::result::{RunResult, Viscosity};
use crate::runner::Control;
use crate::scene::{Observable, Scene};
use crate::sweep::{self, load_finished, run_sweep, Hooks, SweepError, SweepResults};
use dpd_core::observe::Running;
use dpd_core::ParamError;
use serde::Serialize;
use std::path::Path;

/// Relative uncertainty given to each scheme's measured cost per step in an efficiency: the
/// runs share two cores with other work, and repeated runs of the main job differed by up to
/// this much (docs/results.md).
pub const TIMING_UNCERTAINTY: f64 = 0.10;

/// A measured number with its standard error (`None` when it cannot be estimated, e.g. from
/// a single run) and the degrees of freedom of that error (`None`: many).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Value {
    pub value: f64,
    pub sigma: Option<f64>,
    pub dof: Option<usize>,
}

/// Blocks of the viscosity's block error in one run (dpd_core's ShearViscosity).
const VISCOSITY_BLOCKS: usize = 10;

/// What the runs say about one quantity.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "status", rename_all = "snake_case")]
pub enum Measured {
    Value(Value),
    /// A run at this point blew up.
    BlowUp,
    /// Not measured, and why.
    Missing {
        reason: String,
    },
}

fn missing(reason: impl ToString) -> Measured {
    Measured::Missing {
        reason: reason.to_string(),
    }
}

/// Everything an item's runs produced.
#[derive(Clone, Debug, Serialize)]
pub struct Measurements {
    pub scene: Scene,
    /// Every finished run.
    pub points: Vec<RunResult>,
    /// The sweep's aggregation, for an item with `[scene.sweep]`.
    pub sweep: Option<SweepResults>,
}

/// Run `item`'s scene (the `quick` one or the full protocol): its sweep, or the (scheme, dt)
/// points of its published rows times the scene's seeds. The finished runs are written to
/// `out/<id>[.quick].sweep.json` or `.points.json` after every run, and the full protocol
/// resumes from there. `None` for an item without a scene.
pub fn run_item(
    item: &Item,
    quick: bool,
    out: &Path,
    control: Control,
) -> Result<Option<Measurements>, SweepError> {
    let Some(scene) = item
        .scene(quick)
        .map_err(|e| ParamError::new("scene", item.id.clone(), e.to_string()))?
    else {
        return Ok(None);
    };
    let json = out.join(format!(
        "{}{}.{}.json",
        item.id,
        if quick { ".quick" } else { "" },
        if scene.sweep.is_some() {
            "sweep"
        } else {
            "points"
        }
    ));
    // A quick run is always fresh; a full one resumes.
    let finished = if quick {
        Vec::new()
    } else {
        load_finished(&json, &scene)?
    };
    if scene.sweep.is_some() {
        let save = |r: &SweepResults| {
            // A results file that cannot be written only loses resumability.
            let _ = r.write_json(&json);
        };
        let hooks = Hooks {
            control,
            on_point: &save,
        };
        let results = run_sweep(&scene, finished, hooks)?;
        return Ok(Some(Measurements {
            scene,
            points: results.points.clone(),
            sweep: Some(results),
        }));
    }
    let batch = Batch::new(&scene, point_jobs(item, &scene))
        .map_err(|e| ParamError::new("published.scheme", &e.scheme, e.to_string()))?;
    // A file that cannot be written only loses resumability; an interrupted run is kept for
    // this printout and run again by the next invocation.
    let save = |points: &[RunResult]| {
        let _ = sweep::write_finished(&json, &scene, points);
    };
    let mut points = batch.run(finished, control, &save)?;
    points.sort_by(|a, b| {
        (&a.scheme, a.dt, a.seed)
            .partial_cmp(&(&b.scheme, b.dt, b.seed))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    Ok(Some(Measurements {
        scene,
        points,
        sweep: None,
    }))
}

/// The distinct (scheme, dt) of the published rows, times the scene's seeds.
fn point_jobs(item: &Item, scene: &Scene) -> Vec<Job> {
    distinct(item.published.iter().flat_map(|row| {
        let points = row.dt.map(|dt| (row.scheme.clone(), dt));
        points.into_iter().flat_map(|(scheme, dt)| {
            scene.run.seeds().map(move |seed| Job {
                scheme: scheme.clone(),
                dt,
                seed,
            })
        })
    }))
}

/// Mean and standard error of the mean of the `Some` values.
fn mean_of(values: impl Iterator<Item = Option<f64>>) -> Option<Value> {
    let mut r = Running::default();
    values.flatten().for_each(|x| r.push(x));
    let n = r.count() as usize;
    (n > 0).then(|| Value {
        value: r.mean(),
        sigma: (n >= 2).then(|| (r.variance() / n as f64).sqrt()),
        dof: Some(n.saturating_sub(1)),
    })
}

impl Measurements {
    /// The runs of `scheme` at `dt` (within a relative 1e-9).
    pub fn runs_at(&self, scheme: &str, dt: f64) -> Vec<&RunResult> {
        self.points
            .iter()
            .filter(|p| p.scheme == scheme && (p.dt - dt).abs() <= 1e-9 * dt)
            .collect()
    }

    /// `quantity` of `scheme`, at `dt` for the per-point quantities.
    pub fn get(&self, quantity: &str, scheme: &str, dt: Option<f64>) -> Measured {
        match dt {
            Some(dt) => self.at_point(quantity, scheme, dt),
            None => self.of_scheme(quantity, scheme),
        }
    }

    fn at_point(&self, quantity: &str, scheme: &str, dt: f64) -> Measured {
        let runs = self.runs_at(scheme, dt);
        if runs.is_empty() {
            return missing(format!("no run of {scheme} at dt = {dt}"));
        }
        if runs.iter().any(|r| !r.stable) {
            return Measured::BlowUp;
        }
        let kbt = self.scene.physics.kbt;
        let over = |f: &dyn Fn(&RunResult) -> Option<f64>| mean_of(runs.iter().map(|r| f(r)));
        let relative =
            |f: fn(&RunResult) -> Option<f64>| over(&|r| f(r).map(|t| (t - kbt).abs() / kbt));
        let value = match quantity {
            "kinetic_temperature" => over(&|r| r.kinetic_temperature),
            "kinetic_temperature_error" => relative(|r| r.kinetic_temperature),
            "configurational_temperature" => over(&|r| r.configurational_temperature),
            "configurational_temperature_error" => relative(|r| r.configurational_temperature),
            "potential_energy" => over(&|r| r.potential_energy),
            "diffusion" => over(&|r| r.diffusion),
            "channel_temperature" => over(&|r| channel_temperature(r)),
            "shear_viscosity" => {
                let v = Viscosity::combine(&runs.iter().map(|r| r.viscosity).collect::<Vec<_>>());
                v.and_then(|v| {
                    Some(Value {
                        value: v.shear_viscosity?,
                        sigma: v.shear_viscosity_error,
                        dof: Some(runs.len() * (VISCOSITY_BLOCKS - 1)),
                    })
                })
            }
            other => return missing(format!("{other} is a per-scheme quantity (no dt)")),
        };
        value.map_or_else(|| missing("not measured in this scene"), Measured::Value)
    }

    fn of_scheme(&self, quantity: &str, scheme: &str) -> Measured {
        let Some(sweep) = &self.sweep else {
            return missing(format!("{quantity} needs a sweep ([scene.sweep])"));
        };
        let w = self.scene.sweep_spec();
        let Some(summary) = sweep.summary.iter().find(|s| s.scheme == scheme) else {
            return missing(format!("{scheme} is not among the sweep's schemes"));
        };
        match quantity {
            "critical_dt_10" => self.critical(scheme, 0),
            "critical_dt_1" => self.critical(scheme, 1),
            "efficiency" => self.efficiency(scheme, w.reference(), 0),
            "efficiency_1" => self.efficiency(scheme, w.reference(), 1),
            "stability_dt" => summary.stability_dt.map_or(Measured::BlowUp, |dt| {
                Measured::Value(Value {
                    value: dt,
                    sigma: Some(0.5 * dt * (w.dt_factor - 1.0)),
                    dof: None,
                })
            }),
            other => missing(format!("{other} is a per-point quantity (needs dt)")),
        }
    }

    /// The critical dt at threshold `which` of [`sweep::THRESHOLDS`], with half the spread
    /// of the crossings of error - s and error + s (s the standard error of each point's
    /// relative error over the seeds) as its error. Where the error changes sign at the
    /// crossing ([`Critical::SignChange`]) the log-log reading is a guess inside the bracket,
    /// so the standard deviation of a uniform spread over the bracket, (above - below) / sqrt
    /// 12, is added in quadrature.
    fn critical(&self, scheme: &str, which: usize) -> Measured {
        let Some(sweep) = &self.sweep else {
            return missing("not a sweep");
        };
        let threshold = sweep::THRESHOLDS[which];
        let rows: Vec<&Aggregate> = sweep.rows.iter().filter(|r| r.scheme == scheme).collect();
        let base_eta = sweep.baseline.as_ref().and_then(|b| b.shear_viscosity());
        let curve = |shift: f64| -> Vec<(f64, f64)> {
            rows.iter()
                .map(|r| {
                    let e = r.critical_error(sweep.observable);
                    let s = stderr_of_error(r, sweep.observable, self.scene.physics.kbt, base_eta);
                    // A blow-up (infinite error) stays one, and an unshifted curve needs no
                    // error bar (`inf + 0 * NaN` would be NaN).
                    let v = if shift == 0.0 || e.is_infinite() {
                        e
                    } else {
                        e + shift * s.unwrap_or(f64::NAN)
                    };
                    (r.dt, v)
                })
                .collect()
        };
        let Some(mid) = critical_dt(&curve(0.0), threshold) else {
            return missing("no sweep rows");
        };
        let Some(dt) = mid.dt() else {
            return missing(format!("not found inside the grid: {mid}"));
        };
        let bound = |shift| critical_dt(&curve(shift), threshold).and_then(Critical::dt);
        let bracket = match mid {
            Critical::SignChange { below, above, .. } => (above - below) / 12f64.sqrt(),
            _ => 0.0,
        };
        let sigma = bound(1.0)
            .zip(bound(-1.0))
            .map(|(lo, hi)| (0.5 * (hi - lo)).hypot(bracket));
        let dof = match sweep.observable {
            Observable::ConfigurationalTemperature => self.scene.run.runs as usize - 1,
            Observable::Viscosity => self.scene.run.runs as usize * (VISCOSITY_BLOCKS - 1),
        };
        Measured::Value(Value {
            value: dt,
            sigma,
            dof: Some(dof),
        })
    }

    fn efficiency(&self, scheme: &str, reference: &str, which: usize) -> Measured {
        let Some(sweep) = &self.sweep else {
            return missing("not a sweep");
        };
        let cost = |s: &str| sweep.summary.iter().find(|x| x.scheme == s)?.ms_per_step;
        let (Measured::Value(c), Measured::Value(r)) = (
            self.critical(scheme, which),
            self.critical(reference, which),
        ) else {
            return missing("a critical dt is not measured");
        };
        let (Some(ms), Some(ms_ref)) = (cost(scheme), cost(reference)) else {
            return missing("no cost per step");
        };
        let value = (c.value / ms) / (r.value / ms_ref);
        let rel = |v: Value| v.sigma.map(|s| s / v.value);
        let sigma = rel(c).zip(rel(r)).map(|(a, b)| {
            let timing = if scheme == reference {
                0.0
            } else {
                2.0 * TIMING_UNCERTAINTY * TIMING_UNCERTAINTY
            };
            let ab = if scheme == reference {
                0.0
            } else {
                a * a + b * b
            };
            value * (ab + timing).sqrt()
        });
        Measured::Value(Value {
            value,
            sigma,
            dof: c.dof.min(r.dof),
        })
    }
}

/// The standard error of a row's relative error of `observable`.
fn stderr_of_error(
    r: &Aggregate,
    observable: Observable,
    kbt: f64,
    base_eta: Option<f64>,
) -> Option<f64> {
    match observable {
        Observable::ConfigurationalTemperature => {
            r.configurational_temperature_stderr.map(|s| s / kbt)
        }
        Observable::Viscosity => Some(r.viscosity?.shear_viscosity_error? / base_eta?.abs()),
    }
}

/// The particle-weighted mean slab temperature of a run's profile.
fn channel_temperature(r: &RunResult) -> Option<f64> {
    let rows = r.profile.as_ref()?;
    let (sum, count) = rows
        .iter()
        .filter(|p| p.count > 0 && p.temperature.is_finite())
        .fold((0.0, 0u64), |(s, c), p| {
            (s + p.temperature * p.count as f64, c + p.count)
        });
    (count > 0).then(|| sum / count as f64)
}
