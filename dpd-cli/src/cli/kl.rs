//! `dpd kl`: the KL divergence between the configurations a scheme samples and exp(-U/k_B T),
//! estimated from shadow work ([`dpd_measure::kl`]).

use super::scene_flags::SceneFlags;
use super::{bad_input, print_json, progress, INTERRUPTED};
use dpd::error::shown;
use dpd::schemes::registry::resolve;
use dpd_measure::kl::{estimate, KlError, KlSpec};
use dpd_measure::Control;
use std::process::ExitCode;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// Registry name or scheme string made of A, B, O and Ob (e.g. "ABOBA")
    #[arg(id = "kl-scheme", value_name = "SCHEME")]
    scheme: String,
    #[command(flatten)]
    scene: SceneFlags,
    /// Protocol samples (each: an equilibrium state and two halves of the protocol)
    #[arg(long, default_value_t = KlSpec::default().samples)]
    samples: u64,
    /// Length of each half of the protocol, in time units
    #[arg(long, value_name = "T", default_value_t = KlSpec::default().protocol_time)]
    protocol_time: f64,
    /// Monte Carlo sweeps between two equilibrium samples of a chain
    #[arg(long, default_value_t = KlSpec::default().sweeps_between)]
    sweeps_between: u64,
    /// Print one JSON object on stdout
    #[arg(long)]
    json: bool,
}

pub fn main(args: Args) -> ExitCode {
    if let Some(s) = &args.scene.scheme {
        return bad_input(format!(
            "--scheme {s}: give the scheme as the first argument of `dpd kl`"
        ));
    }
    let scene = match args.scene.scene() {
        Ok(scene) => scene,
        Err(e) => return bad_input(e),
    };
    let scheme = match resolve(&args.scheme) {
        Ok(scheme) => scheme,
        Err(e) => return bad_input(format!("invalid scheme: {e}")),
    };
    let spec = KlSpec {
        samples: args.samples,
        protocol_time: args.protocol_time,
        sweeps_between: args.sweeps_between,
        ..KlSpec::default()
    };
    let name = shown(&args.scheme);
    let dt = scene.run.dt;
    let steps = ((spec.protocol_time / dt).round() as u64).max(1);
    match scheme.program() {
        Some(p) => errln!("# dpd: KL estimate of {name} = {p}"),
        None => errln!("# dpd: KL estimate of {name}"),
    }
    errln!(
        "# dt = {}, {} samples of 2 x {steps} steps, {} Monte Carlo sweeps between samples\n\
         # N = {}, density = {}, a = {}, gamma = {}, kbt = {}, mass = {}, weight_exponent = {}, \
         seed = {}",
        dt,
        spec.samples,
        spec.sweeps_between,
        scene.geometry.particles(),
        scene.geometry.density,
        scene.physics.a,
        scene.physics.gamma,
        scene.physics.kbt,
        scene.physics.mass,
        scene.physics.weight_exponent,
        scene.run.seed
    );
    let bar = progress::bar(2 * steps * spec.samples, format!("{name} dt = {dt}"));
    let control = Control {
        stop: progress::stop_flag(),
        progress: &|n| bar.inc(n),
    };
    let result = estimate(&scene, scheme.as_ref(), dt, &spec, control);
    bar.finish_and_clear();
    let r = match result {
        Ok(r) => r,
        Err(KlError::Interrupted) => {
            errln!("dpd: interrupted, no estimate");
            return ExitCode::from(INTERRUPTED);
        }
        Err(KlError::BlowUp(b)) => {
            errln!("dpd: the scheme blew up in a protocol, so it has no stationary distribution at dt = {dt}: {b}");
            return ExitCode::FAILURE;
        }
        Err(e) => return bad_input(e),
    };
    if args.json {
        return print_json(&r);
    }
    outln!(
        "KL divergence of the configurations: {:.4e} +- {:.1e} ({:.3e} per particle, N = {})",
        r.kl_divergence,
        r.kl_error,
        r.kl_per_particle,
        r.particles
    );
    outln!(
        "shadow work in k_B T: <W_F> = {:.4e} +- {:.1e}, <W_R> = {:.4e} +- {:.1e}",
        r.forward_work.mean,
        r.forward_work.error,
        r.reverse_work.mean,
        r.reverse_work.error
    );
    outln!(
        "equilibrium samples: U / N = {:.5} +- {:.1e}",
        r.equilibrium_potential_energy.mean,
        r.equilibrium_potential_energy.error
    );
    outln!(
        "{} samples x 2 x {} steps; Monte Carlo acceptance {:.2}; seconds (all threads): \
         Monte Carlo {:.1}, protocols {:.1}",
        r.samples,
        r.protocol_steps,
        r.acceptance,
        r.sampling_seconds,
        r.protocol_seconds
    );
    ExitCode::SUCCESS
}
