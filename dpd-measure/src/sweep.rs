//! Sweeps: every scheme of a scene's `[sweep]` table over its dt grid and seeds, run in
//! parallel (one point per worker, each single-threaded), resumable from the results file,
//! summarised as critical step sizes, stability thresholds and efficiencies.

use crate::aggregate::{Aggregate, CRITICAL_OBSERVABLES};
use crate::batch::{distinct, unfinished, Batch};
use crate::cost::{self, Cost};
use crate::critical::{critical_dt, Critical};
use crate::result::Job;
use crate::result::RunResult;
use crate::runner::Control;
use crate::scene::section::json_keys;
use crate::scene::{Observable, Scene, SceneError};
use dpd_core::{ParamError, Scheme};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;
use thiserror::Error;

/// The two thresholds of the relative error of the sweep's observable (algorithms.md
/// section 7).
pub const THRESHOLDS: [f64; 2] = [0.10, 0.01];

/// Where the relative error of one observable first reaches 10 % and 1 %.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Crossings {
    pub critical_10: Option<Critical>,
    pub critical_1: Option<Critical>,
}

/// Per scheme: critical step sizes, stability and efficiency.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SchemeSummary {
    pub scheme: String,
    /// dt at 10 % relative error of the sweep's observable, where interpolated inside the grid.
    pub critical_dt_10: Option<f64>,
    /// dt at 1 % relative error, where interpolated inside the grid.
    pub critical_dt_1: Option<f64>,
    /// How each was found (also when it was not: below or above the grid, or next to a
    /// blow-up).
    pub critical_10: Option<Critical>,
    pub critical_1: Option<Critical>,
    /// The same for each observable the sweep measured, keyed by its field name in the rows
    /// ([`CRITICAL_OBSERVABLES`]): T_K and T_C against k_B T, the potential energy, the mean
    /// bond length (with bonds) and the like-neighbour fraction (with `like_neighbours`, the
    /// species that errs most) against the baseline.
    pub critical_steps: BTreeMap<&'static str, Crossings>,
    /// Largest grid dt below the first one where a run blew up (`None` if the smallest did).
    pub stability_dt: Option<f64>,
    /// Smallest grid dt where a run blew up (`None`: stable over the whole grid).
    pub first_blow_up_dt: Option<f64>,
    /// Integration cost in milliseconds per step, measured after the runs (see
    /// [`crate::cost`]); `None` before that or where the scheme blew up while timed.
    pub ms_per_step: Option<f64>,
    pub force_evaluations_per_step: Option<f64>,
    /// (critical_dt_10 / ms_per_step), divided by the same for the reference scheme.
    pub efficiency: Option<f64>,
}

/// Everything a sweep produced; also the resumable results file.
#[derive(Clone, Debug, Serialize)]
pub struct SweepResults {
    /// The effective scene.
    pub scene: Scene,
    /// Whose relative error decides the critical step sizes (also `scene.sweep.observable`).
    pub observable: Observable,
    /// Every finished run.
    pub points: Vec<RunResult>,
    /// Per (scheme, dt) over the seeds, in scheme order then increasing dt.
    pub rows: Vec<Aggregate>,
    /// The small-dt run the potential energy, pressure and viscosity are compared with.
    pub baseline: Option<Aggregate>,
    pub summary: Vec<SchemeSummary>,
    /// How the costs per step of the summary were measured (`None` before the runs ended).
    pub cost: Option<Cost>,
    /// Every planned point is in `points`.
    pub complete: bool,
}

/// The part of a results file that a resumed run reads back: a sweep's results, or the
/// finished runs of a paper item without a sweep ([`write_finished`]).
#[derive(Deserialize)]
struct Stored {
    /// The scene as written: its keys, with null for what was not set.
    scene: serde_json::Value,
    points: Vec<RunResult>,
}

/// What [`write_finished`] writes: the scene and its finished runs, the fields of [`Stored`].
#[derive(Serialize)]
struct Finished<'a> {
    scene: &'a Scene,
    points: &'a [RunResult],
}

/// A sweep that cannot start or cannot keep its results.
#[derive(Debug, Error)]
pub enum SweepError {
    #[error(transparent)]
    Scene(#[from] SceneError),
    #[error("{0}")]
    Invalid(#[from] ParamError),
    #[error("results file {path}: {message}")]
    Results { path: String, message: String },
}

/// Every run of the sweep: schemes x grid x seeds, then the baseline runs not already among
/// them; the longest (smallest dt) first within each scheme.
pub fn plan(scene: &Scene) -> Vec<Job> {
    let w = scene.sweep_spec();
    let baseline = std::iter::once((&w.baseline_scheme, w.baseline_dt()));
    let grid = w
        .schemes
        .iter()
        .flat_map(|s| w.grid().into_iter().map(move |dt| (s, dt)));
    distinct(grid.chain(baseline).flat_map(|(scheme, dt)| {
        scene.run.seeds().map(move |seed| Job {
            scheme: scheme.clone(),
            dt,
            seed,
        })
    }))
}

/// The planned runs of `scene` that are not among `finished`.
pub fn pending(scene: &Scene, finished: &[RunResult]) -> Vec<Job> {
    unfinished(plan(scene), finished)
}

/// Read the finished points of an earlier sweep or paper item of the same physical scene from
/// `path`; nothing if the file does not exist.
pub fn load_finished(path: &Path, scene: &Scene) -> Result<Vec<RunResult>, SweepError> {
    let error = |message: String| SweepError::Results {
        path: path.display().to_string(),
        message,
    };
    let text = match std::fs::read_to_string(path) {
        Ok(text) => text,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => return Err(error(e.to_string())),
    };
    if text.trim().is_empty() {
        // An empty file holds no results to protect.
        return Ok(Vec::new());
    }
    let stored: Stored = serde_json::from_str(&text).map_err(|e| error(e.to_string()))?;
    let was = json_keys(stored.scene)
        .and_then(|keys| Scene::from_keys(keys, "").map_err(|e| e.to_string()))
        .map_err(|e| error(format!("its scene cannot be read: {e}")))?;
    let remedy = "choose another results file or remove it";
    if let Some(key) = physics_difference(&was, scene) {
        return Err(error(format!(
            "it was written for a different scene ({key} differs); {remedy}"
        )));
    }
    let (was, is) = (was.sweep_spec().observable, scene.sweep_spec().observable);
    if was != is {
        return Err(error(format!(
            "it was written for sweep.observable = {}, not {}; {remedy}",
            was.name(),
            is.name()
        )));
    }
    Ok(stored
        .points
        .into_iter()
        .filter(|p| !p.interrupted)
        .collect())
}

/// The first scene key, other than those that only choose runs, in which `a` and `b` differ.
fn physics_difference(a: &Scene, b: &Scene) -> Option<String> {
    let physics = |s: &Scene| -> toml::Table {
        let mut t = toml::Table::try_from(s).unwrap_or_default();
        for key in [
            "description",
            "scheme",
            "allow_inconsistent",
            "dt",
            "seed",
            "runs",
            "threads",
            "sweep",
        ] {
            t.remove(key);
        }
        t
    };
    let (a, b) = (physics(a), physics(b));
    a.keys()
        .chain(b.keys())
        .find(|k| a.get(*k) != b.get(*k))
        .cloned()
}

/// Hooks of a running sweep: `control` for the runs, `on_point` after each finished run with
/// the results so far (to save them).
pub struct Hooks<'a> {
    pub control: Control<'a>,
    pub on_point: &'a (dyn Fn(&SweepResults) + Sync),
}

/// Run the points of `scene`'s sweep that are not in `finished` (which stay in the results,
/// also those outside the plan, of a narrower sweep of the same scene), on
/// `scene.run.threads` workers (0: one per core). Interrupted runs are left out.
pub fn run_sweep(
    scene: &Scene,
    finished: Vec<RunResult>,
    hooks: Hooks,
) -> Result<SweepResults, SweepError> {
    if let Some(t) = &scene.output.trajectory {
        return Err(ParamError::new(
            "trajectory.file",
            t.file.display(),
            "trajectories are written by `dpd run` only: remove [trajectory] for a sweep",
        )
        .into());
    }
    if let Some(file) = &scene.output.write_data {
        return Err(ParamError::new(
            "write_data",
            file.display(),
            "data files are written by `dpd run` only: remove write_data for a sweep",
        )
        .into());
    }
    let batch = Batch::new(scene, plan(scene))
        .map_err(|e| ParamError::new("sweep.schemes", &e.scheme, format!("not a scheme: {e}")))?;
    let completed = |points: &[RunResult]| -> Vec<RunResult> {
        points.iter().filter(|p| !p.interrupted).cloned().collect()
    };
    let save = |points: &[RunResult]| {
        if points.last().is_some_and(|p| !p.interrupted) {
            (hooks.on_point)(&SweepResults::new(scene, completed(points), None));
        }
    };
    let points = batch.run(finished, hooks.control, &save)?;
    let w = scene.sweep_spec();
    let schemes: Vec<_> = w
        .schemes
        .iter()
        .filter_map(|s| Some((s.as_str(), batch.scheme(s)? as &(dyn Scheme + Sync))))
        .collect();
    let cost = cost::measure(scene, &schemes, w.dt_min, hooks.control)?;
    Ok(SweepResults::new(scene, completed(&points), cost))
}

impl SweepResults {
    /// Aggregate `points` of `scene`'s sweep, with the schemes' `cost` per step if measured.
    pub fn new(scene: &Scene, mut points: Vec<RunResult>, cost: Option<Cost>) -> SweepResults {
        let w = scene.sweep_spec();
        let planned = plan(scene);
        let index = |p: &RunResult| planned.iter().position(|j| j.matches(&p.job()));
        points.sort_by_key(|p| index(p).unwrap_or(usize::MAX));
        let complete = planned
            .iter()
            .all(|j| points.iter().any(|p| j.matches(&p.job())));
        let at = |scheme: &str, dt: f64| -> Option<Aggregate> {
            let runs: Vec<&RunResult> = points
                .iter()
                .filter(|p| p.scheme == scheme && (p.dt - dt).abs() <= 1e-9 * dt)
                .collect();
            (!runs.is_empty()).then(|| Aggregate::of(&runs, scene.physics.kbt))
        };
        let baseline = at(&w.baseline_scheme, w.baseline_dt());
        let mut rows: Vec<Aggregate> = w
            .schemes
            .iter()
            .flat_map(|s| w.grid().into_iter().filter_map(move |dt| at(s, dt)))
            .collect();
        if let Some(b) = &baseline {
            rows.iter_mut().for_each(|r| r.compare_with(b));
        }
        let mut summary: Vec<SchemeSummary> = w
            .schemes
            .iter()
            .map(|s| summarise(s, &rows, w.observable, cost.as_ref()))
            .collect();
        let reference = summary
            .iter()
            .find(|s| s.scheme == w.reference())
            .and_then(raw_efficiency);
        for s in &mut summary {
            s.efficiency = raw_efficiency(s).zip(reference).map(|(e, r)| e / r);
        }
        SweepResults {
            scene: scene.clone(),
            observable: w.observable,
            points,
            rows,
            baseline,
            summary,
            cost,
            complete,
        }
    }

    /// Write the results as JSON to `path`, atomically (a temporary file renamed over it).
    pub fn write_json(&self, path: &Path) -> std::io::Result<()> {
        write_atomically(path, self)
    }
}

/// Write `scene` and its finished runs `points` to `path` in the form [`load_finished`] reads
/// back, atomically.
pub fn write_finished(path: &Path, scene: &Scene, points: &[RunResult]) -> std::io::Result<()> {
    write_atomically(path, &Finished { scene, points })
}

/// `value` as pretty JSON to `path`, through a temporary file renamed over it, so that an
/// interruption leaves the old file or the new one.
fn write_atomically(path: &Path, value: &impl Serialize) -> std::io::Result<()> {
    let text = serde_json::to_string_pretty(value).map_err(std::io::Error::other)?;
    let tmp = path.with_extension("json.tmp");
    std::fs::write(&tmp, text)?;
    std::fs::rename(&tmp, path)
}

fn raw_efficiency(s: &SchemeSummary) -> Option<f64> {
    let e = s.critical_dt_10? / s.ms_per_step?;
    e.is_finite().then_some(e)
}

/// Critical step sizes (of `observable`'s error), stability and cost of `scheme` from its
/// `rows` and the measured `cost`.
fn summarise(
    scheme: &str,
    rows: &[Aggregate],
    observable: Observable,
    cost: Option<&Cost>,
) -> SchemeSummary {
    let rows: Vec<&Aggregate> = rows.iter().filter(|r| r.scheme == scheme).collect();
    let crossings = |curve: Vec<(f64, f64)>| THRESHOLDS.map(|t| critical_dt(&curve, t));
    let [c10, c1] = crossings(
        rows.iter()
            .map(|r| (r.dt, r.critical_error(observable)))
            .collect(),
    );
    let critical_steps = CRITICAL_OBSERVABLES
        .iter()
        .filter(|(_, _, error)| rows.iter().any(|r| error(r).is_some()))
        .map(|&(name, _, error)| {
            let [critical_10, critical_1] =
                crossings(rows.iter().map(|r| (r.dt, r.critical(error(r)))).collect());
            let both = Crossings {
                critical_10,
                critical_1,
            };
            (name, both)
        })
        .collect();
    let first_unstable = rows.iter().position(|r| !r.stable);
    let stable_until = first_unstable.unwrap_or(rows.len());
    let stable_rows = || rows.iter().filter(|r| r.stable);
    let mean = |f: fn(&Aggregate) -> Option<f64>| {
        let v: Vec<f64> = stable_rows().filter_map(|r| f(r)).collect();
        (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
    };
    SchemeSummary {
        scheme: scheme.to_string(),
        critical_dt_10: c10.and_then(Critical::dt),
        critical_dt_1: c1.and_then(Critical::dt),
        critical_10: c10,
        critical_1: c1,
        critical_steps,
        stability_dt: stable_until.checked_sub(1).map(|k| rows[k].dt),
        first_blow_up_dt: first_unstable.map(|k| rows[k].dt),
        ms_per_step: cost.and_then(|c| c.of(scheme)),
        force_evaluations_per_step: mean(|r| r.force_evaluations_per_step),
        efficiency: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::result::{ChainSizes, Viscosity};
    use crate::scene::SweepSpec;
    use approx::assert_relative_eq;
    use std::sync::atomic::AtomicUsize;
    use std::sync::atomic::{AtomicBool, Ordering};

    #[test]
    fn an_empty_results_file_holds_no_results() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("empty.json");
        std::fs::write(&path, "\n").unwrap();
        assert!(load_finished(&path, &tiny()).unwrap().is_empty());
        std::fs::write(&path, "{").unwrap();
        assert!(load_finished(&path, &tiny()).is_err());
    }

    fn tiny() -> Scene {
        let mut scene = Scene {
            sweep: Some(SweepSpec {
                schemes: vec!["aboba".into(), "vv".into()],
                dt_min: 0.05,
                dt_max: 0.1,
                dt_factor: 2.0,
                reference: Some("vv".into()),
                baseline_scheme: "aboba".into(),
                baseline_dt: Some(0.025),
                observable: Observable::ConfigurationalTemperature,
            }),
            ..Default::default()
        };
        scene.geometry.n = 100;
        scene.run.time = 1.0;
        scene.run.average_fraction = 0.5;
        scene.run.runs = 2;
        scene.run.threads = 2;
        scene
    }

    fn sweep_counting(scene: &Scene, finished: Vec<RunResult>, ran: &AtomicUsize) -> SweepResults {
        let stop = AtomicBool::new(false);
        let on_point = |_: &SweepResults| {
            ran.fetch_add(1, Ordering::Relaxed);
        };
        let hooks = Hooks {
            control: Control {
                stop: &stop,
                progress: &|_| {},
            },
            on_point: &on_point,
        };
        run_sweep(scene, finished, hooks).unwrap()
    }

    #[test]
    fn plan_covers_schemes_grid_seeds_and_the_baseline_once() {
        let jobs = plan(&tiny());
        // 2 schemes x 2 dt x 2 seeds + 2 baseline runs at dt = 0.025.
        assert_eq!(jobs.len(), 10);
        let mut s = tiny();
        s.sweep.as_mut().unwrap().baseline_dt = Some(0.05);
        assert_eq!(plan(&s).len(), 8);
    }

    #[test]
    fn a_resumed_sweep_runs_only_the_missing_points() {
        let scene = tiny();
        let ran = AtomicUsize::new(0);
        let full = sweep_counting(&scene, Vec::new(), &ran);
        assert!(full.complete && full.points.len() == 10);
        assert_eq!(ran.load(Ordering::Relaxed), 10);

        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("sweep.json");
        let mut partial = full.points.clone();
        partial.truncate(6);
        SweepResults::new(&scene, partial, None)
            .write_json(&path)
            .unwrap();
        let finished = load_finished(&path, &scene).unwrap();
        assert_eq!(finished.len(), 6);
        let again = AtomicUsize::new(0);
        let resumed = sweep_counting(&scene, finished.clone(), &again);
        assert_eq!(again.load(Ordering::Relaxed), 4);
        assert!(resumed.complete);
        // The stored points are kept as read; the others are run again, reproducibly.
        assert_eq!(resumed.points[..6], finished[..]);
        let tc = |r: &SweepResults| -> Vec<_> {
            r.points[6..]
                .iter()
                .map(|p| p.configurational_temperature)
                .collect()
        };
        assert_eq!(tc(&resumed), tc(&full));
    }

    #[test]
    fn a_results_file_of_another_scene_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("sweep.json");
        SweepResults::new(&tiny(), Vec::new(), None)
            .write_json(&path)
            .unwrap();
        let mut other = tiny();
        other.physics.gamma = 40.5;
        let e = load_finished(&path, &other).unwrap_err().to_string();
        assert!(e.contains("gamma"), "{e}");
        let mut viscosity = tiny();
        viscosity.sweep.as_mut().unwrap().observable = Observable::Viscosity;
        let e = load_finished(&path, &viscosity).unwrap_err().to_string();
        assert!(e.contains("sweep.observable"), "{e}");
        let mut more_runs = tiny();
        more_runs.run.runs = 5;
        assert!(load_finished(&path, &more_runs).is_ok());
        assert!(load_finished(&dir.path().join("none.json"), &tiny())
            .unwrap()
            .is_empty());
    }

    /// A stable run of `scheme` at `dt` with T_C = `tc`, costing `ms` per step.
    fn point(scheme: &str, dt: f64, tc: f64, ms: f64) -> RunResult {
        RunResult {
            scheme: scheme.into(),
            dt,
            seed: 1,
            steps: 1,
            completed_steps: 1,
            stable: true,
            samples: 1,
            kinetic_temperature: Some(1.0),
            configurational_temperature: Some(tc),
            potential_energy: Some(1.0),
            pressure: Some(1.0),
            ms_per_step: Some(ms),
            force_evaluations_per_step: Some(1.0),
            pair_distance_evaluations_per_step: Some(1.0),
            ..RunResult::default()
        }
    }

    #[test]
    fn the_viscosity_observable_compares_with_the_baseline() {
        let mut scene = tiny();
        scene.run.runs = 1;
        scene.physics.shear_rate = Some(0.2);
        let w = scene.sweep.as_mut().unwrap();
        w.observable = Observable::Viscosity;
        w.schemes = vec!["vv".into()];
        w.reference = Some("vv".into());
        // Viscosity 2 at the baseline; vv errs 5 % and 20 % (as dt^2; its T_C is exact): 10 %
        // at 0.05 sqrt(2).
        let sheared = |scheme: &str, dt: f64, eta: f64| RunResult {
            viscosity: Some(Viscosity {
                shear_viscosity: Some(eta),
                shear_viscosity_error: Some(0.01),
            }),
            ..point(scheme, dt, 1.0, 1.0)
        };
        let points = vec![
            sheared("vv", 0.05, 2.1),
            sheared("vv", 0.1, 2.4),
            sheared("aboba", 0.025, 2.0),
        ];
        let r = SweepResults::new(&scene, points.clone(), None);
        assert_eq!(r.observable, Observable::Viscosity);
        assert_relative_eq!(
            r.rows[1].shear_viscosity_relative_error.unwrap(),
            0.2,
            max_relative = 1e-12
        );
        assert_relative_eq!(
            r.summary[0].critical_dt_10.unwrap(),
            0.05 * 2f64.sqrt(),
            max_relative = 1e-9
        );
        assert_eq!(
            r.summary[0].critical_1,
            Some(Critical::BelowRange { dt_min: 0.05 })
        );
        // The default observable sees the exact T_C: nothing crosses.
        scene.sweep.as_mut().unwrap().observable = Observable::ConfigurationalTemperature;
        let t = SweepResults::new(&scene, points, None);
        assert_eq!(t.summary[0].critical_dt_10, None);
        // Without a shear rate the viscosity observable is refused by name.
        let mut plain = tiny();
        plain.sweep.as_mut().unwrap().observable = Observable::Viscosity;
        let e = plain.validate().unwrap_err();
        assert_eq!(e.field, "sweep.observable");
        // Between walls neither observable is measured.
        let mut walls = tiny();
        walls.geometry.walls = Some(Default::default());
        walls.geometry.box_lengths = Some([5.0, 5.0, 10.0]);
        assert_eq!(walls.validate().unwrap_err().field, "sweep.observable");
    }

    /// The mean bond length and the like-neighbour fractions cross as the other observables
    /// do, against the baseline; the like-neighbour error is that of the species erring most.
    #[test]
    fn bond_length_and_like_neighbours_have_critical_steps() {
        let mut scene = tiny();
        scene.run.runs = 1;
        scene.sweep.as_mut().unwrap().schemes = vec!["vv".into()];
        scene.sweep.as_mut().unwrap().reference = Some("vv".into());
        let with = |scheme: &str, dt: f64, bond: f64, a: f64, b: f64| RunResult {
            chains: Some(ChainSizes {
                bond_length: bond,
                ..ChainSizes::default()
            }),
            like_neighbours: Some(BTreeMap::from([
                ("A".to_string(), Some(a)),
                ("B".to_string(), Some(b)),
            ])),
            ..point(scheme, dt, 1.0, 1.0)
        };
        // Baseline: bond 0.8, fractions 0.9 and 0.5. vv's bond length errs +5 % and +20 % (as
        // dt^2: 10 % at 0.05 sqrt(2)); species B errs +2 % then +4 %, species A -0.5 % then
        // -20 %: the largest errors are +2 % (B) and -20 % (A), a sign change.
        let points = vec![
            with("vv", 0.05, 0.84, 0.9 * 0.995, 0.51),
            with("vv", 0.1, 0.96, 0.9 * 0.8, 0.52),
            with("aboba", 0.025, 0.8, 0.9, 0.5),
        ];
        let r = SweepResults::new(&scene, points, None);
        assert_relative_eq!(
            r.rows[1].bond_length_error.unwrap(),
            0.2,
            max_relative = 1e-12
        );
        assert_relative_eq!(
            r.rows[0].like_neighbours_error.unwrap(),
            0.02,
            max_relative = 1e-9
        );
        assert_relative_eq!(
            r.rows[1].like_neighbours_error.unwrap(),
            -0.2,
            max_relative = 1e-9
        );
        let steps = &r.summary[0].critical_steps;
        let names: Vec<_> = steps.keys().copied().collect();
        assert_eq!(
            names,
            [
                "bond_length",
                "configurational_temperature",
                "kinetic_temperature",
                "like_neighbours",
                "potential_energy"
            ]
        );
        let bond = steps["bond_length"];
        assert_relative_eq!(
            bond.critical_10.unwrap().dt().unwrap(),
            0.05 * 2f64.sqrt(),
            max_relative = 1e-9
        );
        assert_eq!(bond.critical_1, Some(Critical::BelowRange { dt_min: 0.05 }));
        let Some(Critical::SignChange { dt, below, above }) = steps["like_neighbours"].critical_10
        else {
            panic!("{:?}", steps["like_neighbours"]);
        };
        assert_eq!((below, above), (0.05, 0.1));
        // log |e| linear in log dt from 2 % to 20 %: 10 % at 0.05 x 2^(ln 5 / ln 10).
        assert_relative_eq!(
            dt,
            0.05 * 2f64.powf(5f64.ln() / 10f64.ln()),
            max_relative = 1e-9
        );
        // T_K and T_C exact, U equal to the baseline's: never reached.
        for name in [
            "kinetic_temperature",
            "configurational_temperature",
            "potential_energy",
        ] {
            assert_eq!(
                steps[name].critical_10,
                Some(Critical::NotReached { dt_max: 0.1 }),
                "{name}"
            );
        }
        // A fluid measures neither.
        let fluid = vec![
            point("vv", 0.05, 1.05, 1.0),
            point("aboba", 0.025, 1.0, 1.0),
        ];
        let plain = SweepResults::new(&scene, fluid, None);
        assert_eq!(plain.summary[0].critical_steps.len(), 3);
        assert!(plain.rows[0].bond_length.is_none() && plain.rows[0].like_neighbours.is_none());
    }

    #[test]
    fn efficiency_is_relative_to_the_reference() {
        let scene = tiny();
        // Both errors grow as dt^2 and cross 10 % at 0.05 sqrt(2) (vv) and 0.1 sqrt(2)
        // (aboba, at twice the cost per step): equally efficient. The points' own ms/step
        // (3 for both, as under load) do not count: the measured cost does.
        let points = vec![
            point("vv", 0.05, 1.05, 3.0),
            point("vv", 0.1, 1.2, 3.0),
            point("aboba", 0.1, 1.05, 3.0),
            point("aboba", 0.2, 1.2, 3.0),
        ];
        let mut scene = scene;
        scene.run.runs = 1;
        scene.sweep.as_mut().unwrap().dt_max = 0.2;
        let cost = Cost {
            dt: 0.05,
            window_steps: 10,
            windows: 20,
            ms_per_step: vec![("vv".into(), Some(1.0)), ("aboba".into(), Some(2.0))],
        };
        let untimed = SweepResults::new(&scene, points.clone(), None);
        assert!(untimed.summary.iter().all(|s| s.efficiency.is_none()));
        let r = SweepResults::new(&scene, points, Some(cost));
        let by = |name: &str| r.summary.iter().find(|s| s.scheme == name).unwrap();
        let root2 = 2f64.sqrt();
        assert_relative_eq!(
            by("vv").critical_dt_10.unwrap(),
            0.05 * root2,
            max_relative = 1e-9
        );
        assert_relative_eq!(
            by("aboba").critical_dt_10.unwrap(),
            0.1 * root2,
            max_relative = 1e-9
        );
        assert_eq!(by("vv").efficiency, Some(1.0));
        assert_relative_eq!(by("aboba").efficiency.unwrap(), 1.0, max_relative = 1e-9);
        assert_eq!(
            by("aboba").critical_1,
            Some(Critical::BelowRange { dt_min: 0.1 })
        );
        assert_eq!(by("aboba").critical_dt_1, None);
        assert!(!r.complete && r.baseline.is_none());
    }
}
