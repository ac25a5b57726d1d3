//! `dpd predict`: a scheme's errors and critical steps predicted from the exact stationary
//! statistics of its linear step on the fluid's harmonic modes, T_C's with the leading
//! anharmonic correction ([`dpd_predict`]), without running it.

use super::{bad_input, print_json};
use dpd::metropolis::Metropolis;
use dpd::schemes::registry::resolve;
use dpd_measure::{Keys, Scene};
use dpd_predict::anharmonic;
use dpd_predict::network::{self, PairModel};
use dpd_predict::{Critical, Prediction, Predictor, Spectrum};
use serde::Serialize;
use std::process::ExitCode;
use std::time::Instant;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// Registry names or scheme strings, e.g. aboba "BAOOAB"
    #[arg(id = "predict-schemes", value_name = "SCHEME", required = true)]
    schemes: Vec<String>,
    /// Time steps to print the errors at
    #[arg(
        long,
        value_delimiter = ',',
        allow_negative_numbers = true,
        default_value = "0.02,0.04,0.06,0.08,0.1,0.12"
    )]
    dt: Vec<f64>,
    #[command(flatten)]
    spectrum: SpectrumArgs,
    /// Read the observables at the processed positions x + C dt^2 F(x) / m (one force
    /// evaluation per sample): a number C, or `leading` for the C that cancels the leading
    /// dt^2 term of the predicted T_C error, per scheme
    #[arg(long, value_name = "C|leading", value_parser = processing, allow_negative_numbers = true)]
    processing: Option<Processing>,
    /// Print one JSON object on stdout
    #[arg(long)]
    json: bool,
}

/// Where the modes of a prediction come from (`dpd predict`, `dpd orderings --rank
/// predicted`, `dpd design --objective predicted`).
#[derive(Debug, clap::Args)]
pub struct SpectrumArgs {
    /// Scene file (TOML) whose pair forces and density give the modes; default: the standard
    /// gamma = 4.5 box
    #[arg(long, value_name = "FILE")]
    pub scene: Option<std::path::PathBuf>,
    /// Friction gamma (replaces the scene's)
    #[arg(long, allow_negative_numbers = true)]
    pub gamma: Option<f64>,
    /// Particles of the configuration whose pair network gives the modes (a cube at the
    /// scene's density; the dense eigendecomposition costs (3N)^3)
    #[arg(long, default_value_t = DEFAULT_SPECTRUM_PARTICLES, allow_negative_numbers = true)]
    pub spectrum_particles: usize,
}

/// Particles of the spectrum's configuration unless `--spectrum-particles` says otherwise.
const DEFAULT_SPECTRUM_PARTICLES: usize = 256;

impl Default for SpectrumArgs {
    fn default() -> Self {
        SpectrumArgs {
            scene: None,
            gamma: None,
            spectrum_particles: DEFAULT_SPECTRUM_PARTICLES,
        }
    }
}

/// The spectrum the flags ask for, with the scene's friction and the seconds it took, or the
/// message of bad input.
pub fn spectrum_of(args: &SpectrumArgs) -> Result<(Spectrum, f64, f64), String> {
    let mut keys = Keys::new();
    if let Some(gamma) = args.gamma {
        keys.insert("gamma".into(), gamma.into());
    }
    let scene = Scene::resolve(args.scene.as_deref(), &keys).map_err(|e| e.to_string())?;
    if let Some(why) = not_equilibrium(&scene) {
        return Err(format!(
            "the scene has {why}: predictions are for the periodic bulk at equilibrium"
        ));
    }
    if scene.species.species.is_some() || scene.geometry.init.is_some() {
        return Err(
            "the scene has [[species]] or init: predictions are for one species of the \
             scene's a and mass from a random start"
                .into(),
        );
    }
    if !SPECTRUM_PARTICLES.contains(&args.spectrum_particles) {
        return Err(format!(
            "invalid --spectrum-particles = {}: allowed are {} to {}",
            args.spectrum_particles,
            SPECTRUM_PARTICLES.start(),
            SPECTRUM_PARTICLES.end()
        ));
    }
    let start = Instant::now();
    let spectrum = scene_spectrum(&scene, args.spectrum_particles)?;
    Ok((spectrum, scene.physics.gamma, start.elapsed().as_secs_f64()))
}

/// Fewest and most particles of the spectrum's configuration: below 64 the box is under two
/// cut-offs wide at density 3; above 1000 the eigendecomposition takes minutes.
const SPECTRUM_PARTICLES: std::ops::RangeInclusive<usize> = 64..=1000;

/// Monte Carlo sweeps from uniform positions to the configuration of the spectrum.
const EQUILIBRATION_SWEEPS: u64 = 200;

/// Configurations the anharmonic response is measured on, and Monte Carlo sweeps between them.
const RESPONSE_SAMPLES: usize = 800;
const RESPONSE_SWEEPS: usize = 2;

/// The JSON of `dpd predict`.
#[derive(Debug, Serialize)]
struct Output {
    /// The spectrum's origin: particles, modes, and the seconds it took.
    spectrum_particles: usize,
    modes: usize,
    /// Groups of similar modes solved for (`Spectrum::grouped`).
    groups: usize,
    max_omega2: f64,
    /// How T_C responds to the pairs inside the cut-off (the anharmonic correction's factor).
    response: Option<anharmonic::Response>,
    spectrum_seconds: f64,
    gamma: f64,
    schemes: Vec<SchemeOutput>,
}

/// `--processing`: a given C or the one that cancels the leading error.
#[derive(Clone, Copy, Debug)]
enum Processing {
    Given(f64),
    Leading,
}

fn processing(text: &str) -> Result<Processing, String> {
    if text == "leading" {
        return Ok(Processing::Leading);
    }
    match text.parse::<f64>() {
        Ok(c) if c.is_finite() => Ok(Processing::Given(c)),
        _ => Err(format!(
            "invalid --processing = {text}: allowed are a finite number C or `leading`"
        )),
    }
}

#[derive(Debug, Serialize)]
struct SchemeOutput {
    scheme: String,
    program: String,
    /// C of the position processor the observables are read at (0: unprocessed).
    processing: f64,
    #[serde(flatten)]
    prediction: Prediction,
    /// Milliseconds of the prediction itself (the spectrum is shared).
    milliseconds: f64,
}

pub fn main(args: Args) -> ExitCode {
    if let Some(dt) = args.dt.iter().find(|dt| !(dt.is_finite() && **dt > 0.0)) {
        return bad_input(format!(
            "invalid --dt = {dt}: steps must be finite and positive"
        ));
    }
    let mut programs = Vec::new();
    for name in &args.schemes {
        let scheme = match resolve(name) {
            Ok(s) => s,
            Err(e) => return bad_input(format!("invalid scheme: {e}")),
        };
        match scheme.program() {
            Some(p) => programs.push((name.clone(), p.clone())),
            None => {
                return bad_input(format!(
                    "scheme {name} is hand-written: it has no program of letters to predict"
                ))
            }
        }
    }
    let (spectrum, gamma, spectrum_seconds) = match spectrum_of(&args.spectrum) {
        Ok(s) => s,
        Err(e) => return bad_input(e),
    };
    let predictor = Predictor::new(&spectrum);
    let mut schemes = Vec::new();
    for (name, program) in programs {
        let start = Instant::now();
        let c = match args.processing {
            None => Ok(0.0),
            Some(Processing::Given(c)) => Ok(c),
            Some(Processing::Leading) => match predictor.leading_processing(&program) {
                Ok(Some(c)) => Ok(c),
                Ok(None) => {
                    return bad_input(format!(
                        "scheme {name} is unstable at dt {}: no processing to choose",
                        dpd_predict::predict::PROCESSING_DT
                    ))
                }
                Err(e) => Err(e),
            },
        };
        let predicted = c.and_then(|c| {
            Ok((
                c,
                predictor.clone().processed(c).predict(&program, &args.dt)?,
            ))
        });
        let (processing, prediction) = match predicted {
            Ok(p) => p,
            Err(e) => return bad_input(format!("scheme {name}: {e}")),
        };
        schemes.push(SchemeOutput {
            scheme: name,
            program: program.to_string(),
            processing,
            prediction,
            milliseconds: start.elapsed().as_secs_f64() * 1e3,
        });
    }
    let out = Output {
        spectrum_particles: spectrum.particles,
        modes: spectrum.modes.len(),
        groups: predictor.groups(),
        max_omega2: spectrum.max_omega2(),
        response: spectrum.response,
        spectrum_seconds,
        gamma,
        schemes,
    };
    if args.json {
        return print_json(&out);
    }
    print_text(&out);
    ExitCode::SUCCESS
}

/// Why the scene is not a periodic bulk at equilibrium, if it is not.
fn not_equilibrium(scene: &Scene) -> Option<&'static str> {
    if scene.geometry.walls.is_some() {
        Some("walls")
    } else if scene.physics.sheared() {
        Some("a shear rate")
    } else if scene.physics.body_force.is_some() {
        Some("a body force")
    } else {
        None
    }
}

/// The modes of the pair network of one equilibrium configuration of `particles` particles at
/// the scene's density and pair forces, sampled by a Monte Carlo chain on exp(-U / k_B T)
/// (no integrator bias).
fn scene_spectrum(scene: &Scene, particles: usize) -> Result<Spectrum, String> {
    let (physics, seed) = (&scene.physics, scene.run.seed);
    let params = physics.params().map_err(|e| e.to_string())?;
    let bx = dpd::init::cubic_box(particles, scene.geometry.density).map_err(|e| e.to_string())?;
    let q = dpd::init::uniform_positions(&bx, particles, seed);
    let mut mc =
        Metropolis::new(params, bx, &q, vec![0; particles], seed).map_err(|e| e.to_string())?;
    mc.equilibrate(EQUILIBRATION_SWEEPS);
    let positions = |mc: &Metropolis| -> Vec<[f64; 3]> {
        mc.positions().iter().map(|x| [x.x, x.y, x.z]).collect()
    };
    let q = positions(&mc);
    let l = bx.lengths();
    let edges = [l.x, l.y, l.z];
    let masses = vec![physics.mass; particles];
    let model = PairModel {
        a: physics.a,
        rc: 1.0,
        gamma: physics.gamma,
        weight_exponent: physics.weight_exponent,
        kbt: physics.kbt,
    };
    let mut spectrum = network::spectrum(&q, &masses, edges, model).map_err(|e| e.to_string())?;
    let configs: Vec<Vec<[f64; 3]>> = (0..RESPONSE_SAMPLES)
        .map(|_| {
            (0..RESPONSE_SWEEPS).for_each(|_| mc.sweep());
            positions(&mc)
        })
        .collect();
    spectrum.response =
        Some(anharmonic::response(&configs, &masses, edges, model).map_err(|e| e.to_string())?);
    Ok(spectrum)
}

fn print_text(out: &Output) {
    outln!(
        "# spectrum: {} modes of {} particles in {} groups (largest omega^2 = {:.1}), gamma = {}, \
         {:.2} s",
        out.modes,
        out.spectrum_particles,
        out.groups,
        out.max_omega2,
        out.gamma,
        out.spectrum_seconds
    );
    if let Some(r) = out.response {
        outln!(
            "# anharmonic response R = {:.1} +- {:.1} ({} configurations)",
            r.r,
            r.std_error,
            r.samples
        );
    }
    for s in &out.schemes {
        outln!("\n{} = {}", s.scheme, s.program);
        if s.processing != 0.0 {
            outln!("observables at x + {} dt^2 F(x) / m", s.processing);
        }
        outln!(
            "{:>8}  {:>9}  {:>9}  {:>10}  {:>10}",
            "dt",
            "T_C err %",
            "T_K err %",
            "dU/N",
            "dP"
        );
        for row in &s.prediction.rows {
            let dt = row.dt;
            match row.errors {
                Some(e) => outln!(
                    "{:>8}  {:>+9.3}  {:>+9.3}  {:>+10.4}  {:>+10.4}",
                    dt,
                    100.0 * e.configurational_temperature,
                    100.0 * e.kinetic_temperature,
                    e.potential_energy,
                    e.pressure
                ),
                None => outln!("{dt:>8}  unstable"),
            }
        }
        let p = &s.prediction;
        outln!(
            "dt_c 10 %: {}   dt_c 1 %: {}   stability limit: {}   ({:.1} ms)",
            critical(p.critical_dt_10),
            critical(p.critical_dt_1),
            p.stability_limit
                .map_or("none below 2".into(), |dt| format!("{dt:.4}")),
            s.milliseconds
        );
    }
}

fn critical(c: Critical) -> String {
    match c {
        Critical::At { dt } => format!("{dt:.4}"),
        Critical::StabilityLimit { dt } => format!("{dt:.4} (stability limit)"),
        Critical::NotReached { dt_max } => format!("> {dt_max}"),
    }
}
