//! `dpd sweep` and the main job: schemes over a geometric range of dt, reported as tables,
//! CSV, JSON (also the resumable results file) and SVG plots.

use super::run::header;
use super::scene_flags::{SceneFlags, SweepFlags};
use super::{bad_input, progress, INTERRUPTED};
use dpd_measure::sweep::{self, load_finished, run_sweep, Hooks};
use dpd_measure::{plot, report, Control, Scene, SweepResults};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::Ordering;

/// The main job's scene: the standard gamma = 4.5 comparison, shortened.
const MAIN_SCENE: &str = include_str!("../../../scenes/main.toml");

#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    scene: SceneFlags,
    #[command(flatten)]
    sweep: SweepFlags,
    /// Results file: written after every finished point and read back to resume
    /// [default: OUT/sweep.json]
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
    /// Directory of the CSV table and SVG plots
    #[arg(long, value_name = "DIR", default_value = "results")]
    out: PathBuf,
    /// Ignore an existing results file and start afresh
    #[arg(long)]
    fresh: bool,
}

pub fn main(args: Args) -> ExitCode {
    let scene = match args.sweep.keys().and_then(|k| args.scene.scene_with(&k)) {
        Ok(scene) => scene,
        Err(e) => return bad_input(e),
    };
    let json = args.json.unwrap_or_else(|| args.out.join("sweep.json"));
    execute(&scene, &json, &args.out, args.fresh)
}

/// The main job: `scenes/main.toml` swept into `results/`, resuming an interrupted run.
pub fn main_job() -> ExitCode {
    let scene = match Scene::from_toml(MAIN_SCENE, "scenes/main.toml") {
        Ok(scene) => scene,
        Err(e) => return bad_input(e),
    };
    if let Err(e) = scene.validate() {
        return bad_input(e);
    }
    errln!("dpd: the main job (scenes/main.toml); `dpd --help` lists the commands");
    let out = Path::new("results");
    execute(&scene, &out.join("main.json"), out, false)
}

fn execute(scene: &Scene, json: &Path, out: &Path, fresh: bool) -> ExitCode {
    let (results, written) = match measure(scene, json, out, fresh) {
        Ok(done) => done,
        Err(code) => return code,
    };
    let w = scene.sweep_spec();
    out!("{}", report::rows_table(&results.rows));
    outln!();
    outln!(
        "critical dt: where the relative error of the {} first reaches 10 % / 1 %",
        w.observable.name().replace('-', " ")
    );
    out!("{}", report::summary_table(&results.summary, w.reference()));
    if let Some(cost) = &results.cost {
        outln!("{}", cost.describe());
    }
    outln!();
    outln!(
        "critical dt of each observable: T_K and T_C against k_B T, the others against the \
         baseline ({} at dt = {}); *: the error changes sign around the crossing; (a, b]: the \
         run at b blew up first",
        w.baseline_scheme,
        w.baseline_dt()
    );
    out!("{}", report::critical_table(&results.summary));
    finish(&results, written, scene)
}

/// Run (or resume) the sweep of `scene` with a progress bar, keeping the results in `json`
/// after every point, and write the CSV and plots into `out`: the results and the names of
/// the files written (or why not). `Err` is the exit code of input that cannot run.
pub fn measure(
    scene: &Scene,
    json: &Path,
    out: &Path,
    fresh: bool,
) -> Result<(SweepResults, Result<Vec<String>, String>), ExitCode> {
    let w = scene.sweep_spec();
    let grid = w.grid();
    let ends: Vec<f64> = grid
        .first()
        .into_iter()
        .chain(grid.last())
        .copied()
        .collect();
    let what = format!("sweep of {}", w.schemes.join(", "));
    err!("{}", header(scene, &what, &ends));
    let finished = if fresh {
        Vec::new()
    } else {
        load_finished(json, scene).map_err(bad_input)?
    };
    let pending = sweep::pending(scene, &finished);
    let planned = pending.len() + finished.len();
    // The file may hold points of other schemes or steps: kept, not counted as this plan's.
    let plan = sweep::plan(scene).len();
    let done = plan - pending.len();
    let others = match finished.len().saturating_sub(done) {
        0 => String::new(),
        k => format!(" (and {k} other points it keeps)"),
    };
    errln!(
        "# {} dt from {} to {}; {plan} points, {done} already in {}{others}",
        grid.len(),
        w.dt_min,
        w.dt_max,
        json.display()
    );
    if let Err(e) = std::fs::create_dir_all(out) {
        return Err(bad_input(format!("cannot create {}: {e}", out.display())));
    }
    let total: u64 = pending.iter().map(|j| scene.run.steps(j.dt)).sum();
    let bar = progress::bar(total, format!("{} points", pending.len()));
    let save = |r: &SweepResults| {
        bar.set_message(format!("{} of {planned} points", r.points.len()));
        // Not `bar.println`, which prints nothing where stderr is not a terminal.
        if let Err(e) = r.write_json(json) {
            bar.suspend(|| errln!("dpd: warning: cannot write {}: {e}", json.display()));
        }
    };
    let hooks = Hooks {
        control: Control {
            stop: progress::stop_flag(),
            progress: &|n| bar.inc(n),
        },
        on_point: &save,
    };
    let results = run_sweep(scene, finished, hooks).map_err(bad_input)?;
    bar.finish_and_clear();
    let written = write_outputs(&results, json, out);
    Ok((results, written))
}

/// Report the files written and an interruption: the exit code of a finished sweep.
pub fn finish(
    results: &SweepResults,
    written: Result<Vec<String>, String>,
    scene: &Scene,
) -> ExitCode {
    match written {
        Ok(files) => outln!("wrote {}", files.join(", ")),
        Err(e) => {
            errln!("dpd: error: {e}");
            return ExitCode::FAILURE;
        }
    }
    if progress::stop_flag().load(Ordering::Relaxed) && !results.complete {
        outln!(
            "interrupted: {} of {} points done; run the same command again to resume",
            results.points.len(),
            sweep::plan(scene).len()
        );
        return ExitCode::from(INTERRUPTED);
    }
    ExitCode::SUCCESS
}

/// Write the JSON results, the CSV rows and the plots; the names of the files written.
fn write_outputs(results: &SweepResults, json: &Path, out: &Path) -> Result<Vec<String>, String> {
    let fail =
        |path: &Path, e: &dyn std::fmt::Display| format!("cannot write {}: {e}", path.display());
    results.write_json(json).map_err(|e| fail(json, &e))?;
    let stem = json
        .file_stem()
        .map_or("sweep".into(), |s| s.to_string_lossy());
    let csv = out.join(format!("{stem}.csv"));
    std::fs::write(&csv, report::rows_csv(&results.rows)).map_err(|e| fail(&csv, &e))?;
    let plots = plot::write_plots(results, out).map_err(|e| fail(out, &e))?;
    Ok([json.to_path_buf(), csv]
        .into_iter()
        .chain(plots)
        .map(|p| p.display().to_string())
        .collect())
}
