//! `dpd run`: one scene with one scheme; prints the observables averaged over the runs.

use super::scene_flags::{ObserveFlags, SceneFlags};
use super::{bad_input, print_json, progress, INTERRUPTED};
use dpd::error::shown;
use dpd_measure::plot::profile_plot;
use dpd_measure::scene::section::merge;
use dpd_measure::scene::{ProfileSpec, TrajectorySpec};
use dpd_measure::{report, Aggregate, Batch, Control, Job, Keys, RunResult, Scene, SceneError};
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    scene: SceneFlags,
    /// Print one JSON object on stdout instead of the table
    #[arg(long)]
    json: bool,
    /// With `[profile]`: write each run's profile as `profile-seed<k>.csv` and `.svg` here
    #[arg(long, value_name = "DIR")]
    profile_dir: Option<PathBuf>,
    /// Write a trajectory here (.gsd, .xyz, .lammpstrj/.dump); replaces the scene's [trajectory]
    #[arg(long, value_name = "FILE", requires = "every")]
    trajectory: Option<PathBuf>,
    /// Time between trajectory frames (with --trajectory)
    #[arg(long, value_name = "T", requires = "trajectory")]
    every: Option<f64>,
    /// Start from a frame of a GSD file, FILE.gsd (its last frame) or FILE.gsd:K, or from a
    /// LAMMPS data file, FILE.data; the trajectory's step, time and images go on from the
    /// frame's
    #[arg(long, value_name = "FILE.gsd[:K]|FILE.data")]
    init: Option<String>,
    /// Write each run's last state as a LAMMPS data file (FILE.data; with several runs, run
    /// seed k writes FILE-seedk.data); replaces the scene's write_data
    #[arg(long, value_name = "FILE.data")]
    write_data: Option<PathBuf>,
    /// With --init: count the trajectory's step, time and images from 0 instead
    #[arg(long, requires = "init")]
    init_reset: bool,
    #[command(flatten)]
    observe: ObserveFlags,
}

/// What `dpd run --json` prints: the combined observables of the runs, their details and the
/// effective scene.
#[derive(Serialize)]
struct RunReport<'a> {
    #[serde(flatten)]
    combined: Aggregate,
    steps: u64,
    /// Some run was stopped by Ctrl-C; the observables cover what it sampled.
    interrupted: bool,
    /// The merged stages of the scheme, where it is written in the scheme language.
    program: Option<String>,
    results: &'a [RunResult],
    scene: &'a Scene,
    /// [`Scene::init_coefficients`]: heading to lines.
    init_coefficients: BTreeMap<String, Vec<String>>,
}

pub fn main(args: Args) -> ExitCode {
    let scene = args.observe.keys().and_then(|mut keys| {
        merge(&mut keys, &init_keys(&args));
        args.scene.scene_with(&keys)
    });
    let scene = match scene.and_then(|s| with_files(s, &args)) {
        Ok(scene) => scene,
        Err(e) => return bad_input(e),
    };
    let (run, dt) = (&scene.run, scene.run.dt);
    let jobs: Vec<Job> = run
        .seeds()
        .map(|seed| Job {
            scheme: run.scheme.clone(),
            dt,
            seed,
        })
        .collect();
    let batch = match Batch::new(&scene, jobs) {
        Ok(batch) => batch,
        Err(e) => return bad_input(format!("invalid scheme: {e}")),
    };
    let program = batch
        .scheme(&run.scheme)
        .and_then(|s| s.program())
        .map(|p| p.to_string());
    let name = shown(&run.scheme);
    let what = match &program {
        Some(p) => format!("scheme {name} = {p}"),
        None => format!("scheme {name}"),
    };
    err!("{}", header(&scene, &what, &[dt]));
    let bar = progress::bar(
        run.steps(dt) * run.runs,
        format!("{name} dt = {}", shown(&dt.to_string())),
    );
    let control = Control {
        stop: progress::stop_flag(),
        progress: &|n| bar.inc(n),
    };
    let outcome = batch.run(Vec::new(), control, &|_| {});
    bar.finish_and_clear();
    let mut results = match outcome {
        Ok(results) => results,
        Err(e) => return bad_input(e),
    };
    results.sort_by_key(|r| r.seed);
    let refs: Vec<&RunResult> = results.iter().collect();
    let report = RunReport {
        combined: Aggregate::of(&refs, scene.physics.kbt),
        steps: run.steps(dt),
        interrupted: results.len() < batch.jobs().len() || results.iter().any(|r| r.interrupted),
        program,
        results: &results,
        scene: &scene,
        init_coefficients: scene.init_coefficients().into_iter().collect(),
    };
    if let Some(dir) = &args.profile_dir {
        if let Err(e) = write_profiles(&results, scene.observe.profile.as_ref(), dir) {
            errln!("error: writing profiles to {}: {e}", dir.display());
            return ExitCode::FAILURE;
        }
    }
    let code = if args.json {
        print_json(&report)
    } else {
        print_table(&report);
        ExitCode::SUCCESS
    };
    if report.interrupted {
        ExitCode::from(INTERRUPTED)
    } else {
        code
    }
}

/// `--init` and `--init-reset` as scene keys: they join the scene's before it is read, so that
/// the file's particle count and box fill in what the scene file and flags leave out.
fn init_keys(args: &Args) -> Keys {
    let mut keys = Keys::new();
    if let Some(init) = &args.init {
        keys.insert("init".into(), init.clone().into());
    }
    if args.init_reset {
        keys.insert("init_reset".into(), true.into());
    }
    keys
}

/// `scene` with `--trajectory`/`--every` and `--write-data` applied, validated.
fn with_files(mut scene: Scene, args: &Args) -> Result<Scene, SceneError> {
    if let (Some(file), Some(every)) = (&args.trajectory, args.every) {
        scene.output.trajectory = Some(TrajectorySpec::new(file.clone(), every));
    }
    if let Some(file) = &args.write_data {
        scene.output.write_data = Some(file.clone());
    }
    scene.validate()?;
    Ok(scene)
}

/// Every effective parameter as TOML, after a comment line on `what` and on the steps and
/// sampling at each of `dts`.
pub fn header(scene: &Scene, what: &str, dts: &[f64]) -> String {
    let mut out = format!("# dpd: {what}\n");
    for &dt in dts {
        out += &format!(
            "# at dt = {}: {} steps, a sample every {} steps in the last {} %\n",
            shown(&format!("{dt:.4}")),
            scene.run.steps(dt),
            scene.run.sample_every(dt),
            100.0 * scene.run.average_fraction
        );
    }
    out + &scene.to_toml() + "\n"
}

fn print_table(r: &RunReport) {
    let mut rows: Vec<Aggregate> = r
        .results
        .iter()
        .map(|run| Aggregate {
            scheme: format!("seed {}", run.seed),
            ..Aggregate::of(&[run], r.scene.physics.kbt)
        })
        .collect();
    if rows.len() > 1 {
        rows.push(Aggregate {
            scheme: "mean".into(),
            ..r.combined.clone()
        });
    }
    out!("{}", report::rows_table(&rows));
    let c = &r.combined;
    if let Some(f) = c.force_evaluations_per_step {
        outln!("force evaluations per step: {f:.3}");
    }
    if let Some(d) = c.diffusion {
        outln!("diffusion coefficient: {d:.5}");
    }
    if let Some(a) = c.acceptance {
        outln!("acceptance (Metropolis-adjusted): {a:.4}");
    }
    if let (Some(q), Some(w)) = (c.heat, c.shadow_work) {
        outln!("per particle and time unit, in k_B T: heat {q:.4e}, shadow work {w:.4e}");
    }
    if let Some(v) = c.viscosity {
        match v.shear_viscosity.zip(v.shear_viscosity_error) {
            Some((eta, e)) => outln!("shear viscosity: {eta:.4} +- {e:.4}"),
            None => outln!("shear viscosity: too few samples"),
        }
    }
    for run in r.results {
        if let Some(c) = &run.chains {
            let shown = |x: Option<f64>| x.map_or("none".into(), |x| format!("{x:.4}"));
            outln!(
                "seed {}: mean bond length {:.4}; {} linear chains: <R_ee^2> {}, <R_g^2> {}",
                run.seed,
                c.bond_length,
                c.chains,
                shown(c.end_to_end_squared),
                shown(c.gyration_squared)
            );
        }
        if let Some(like) = &run.like_neighbours {
            let shown = |f: &Option<f64>| f.map_or("none".into(), |f| format!("{f:.4}"));
            let each: Vec<String> = like
                .iter()
                .map(|(s, f)| format!("{s} {}", shown(f)))
                .collect();
            outln!(
                "seed {}: like neighbours within r_c: {}",
                run.seed,
                each.join(", ")
            );
        }
    }
    for run in r.results.iter().filter(|run| !run.stable) {
        outln!(
            "seed {}: {}",
            run.seed,
            run.error.as_deref().unwrap_or("unstable")
        );
    }
    if r.interrupted {
        outln!("interrupted: the averages cover the samples taken before Ctrl-C");
    }
}

/// Write `profile-seed<k>.csv` and `.svg` into `dir` for every run with a profile.
fn write_profiles(
    results: &[RunResult],
    spec: Option<&ProfileSpec>,
    dir: &Path,
) -> Result<(), Box<dyn std::error::Error>> {
    let Some(spec) = spec else {
        return Err("--profile-dir needs a [profile] table in the scene".into());
    };
    std::fs::create_dir_all(dir)?;
    for r in results {
        if let Some(rows) = &r.profile {
            let stem = dir.join(format!("profile-seed{}", r.seed));
            let csv = std::fs::File::create(stem.with_extension("csv"))?;
            dpd::observe::write_profile_csv(spec.axis, rows, std::io::BufWriter::new(csv))?;
            profile_plot(rows, spec.axis, &stem.with_extension("svg"))?;
            errln!("wrote {}.csv and .svg", stem.display());
        }
        if let Some(species) = &r.species_profile {
            let path = dir.join(format!("species-profile-seed{}.csv", r.seed));
            std::fs::write(&path, species_csv(spec.axis, species))?;
            errln!("wrote {}", path.display());
        }
    }
    Ok(())
}

/// The species' slab densities as CSV: the axis (`x`, `y` or `z`), then one column per
/// species.
fn species_csv(axis: usize, species: &BTreeMap<String, Vec<[f64; 2]>>) -> String {
    let names: Vec<&str> = species.keys().map(String::as_str).collect();
    let mut out = format!("{},{}\n", ["x", "y", "z"][axis.min(2)], names.join(","));
    let slabs = species.values().next().map_or(0, Vec::len);
    for k in 0..slabs {
        let mut row = vec![species.values().next().map_or(0.0, |v| v[k][0]).to_string()];
        row.extend(species.values().map(|v| v[k][1].to_string()));
        out += &(row.join(",") + "\n");
    }
    out
}
