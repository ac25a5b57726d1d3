//! One run: a scene's system advanced with one scheme at one time step, observables sampled at
//! the end of full steps, integration timed on its own.

use super::flows::{FlowObservers, Viscosity};
use super::scene::Scene;
use super::trajectory::Recorder;
use dpd_core::observe::{
    balance_defined, thermo, EnergyBalance, ProfileRow, Rdf, ThermoAverages, Vacf,
};
use dpd_core::{ParamError, Scheme};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// What one run is: a scheme (registry name or scheme string), a time step and a seed.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Job {
    pub scheme: String,
    pub dt: f64,
    pub seed: u64,
}

impl Job {
    /// Same scheme and seed, and dt equal to a relative 1e-9 (grids are recomputed).
    pub fn matches(&self, other: &Job) -> bool {
        self.scheme == other.scheme
            && self.seed == other.seed
            && (self.dt - other.dt).abs() <= 1e-9 * self.dt.abs().max(other.dt.abs())
    }
}

/// The outcome of one run. Observables are `None` when no sample was taken (a run that blew
/// up or was stopped before the averaging window).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunResult {
    pub scheme: String,
    pub dt: f64,
    pub seed: u64,
    /// Steps asked for.
    pub steps: u64,
    /// Steps done without blow-up.
    pub completed_steps: u64,
    /// False when the run blew up; `error` then says where and why.
    pub stable: bool,
    pub error: Option<String>,
    /// Stopped by the user before the end; the observables cover the samples taken so far.
    pub interrupted: bool,
    /// Samples in the averages.
    pub samples: u64,
    /// k_B T_K.
    pub kinetic_temperature: Option<f64>,
    /// k_B T_C, the ratio of the averaged numerator and denominator (`None` with `[walls]`).
    pub configurational_temperature: Option<f64>,
    /// Potential energy per particle.
    pub potential_energy: Option<f64>,
    /// Virial pressure (`None` with `[walls]`).
    pub pressure: Option<f64>,
    /// Wall-clock milliseconds per step of the integration alone (no sampling). In a sheared
    /// scene this includes the recording of pair impulses for the stress, which the sweeps do
    /// during the averaging window (a tensor update per pair); with `energy_balance`, the two
    /// kinetic-energy sums per sweep of the heat recording.
    pub ms_per_step: Option<f64>,
    /// Force evaluations per step, counted during the integration.
    pub force_evaluations_per_step: Option<f64>,
    /// Pair-distance evaluations per step, counted during the integration.
    pub pair_distance_evaluations_per_step: Option<f64>,
    /// `[r, g(r)]` per bin, with `[rdf]` in the scene.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rdf: Option<Vec<[f64; 2]>>,
    /// Diffusion coefficient from the velocity autocorrelation, with `[vacf]` in the scene.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub diffusion: Option<f64>,
    /// With a non-zero `shear_rate`: the shear viscosity and its error (null with too few
    /// samples).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub viscosity: Option<Viscosity>,
    /// Slab profile with `[profile]` in the scene.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub profile: Option<Vec<ProfileRow>>,
    /// With `energy_balance`: heat taken up from the thermostat per particle and time unit, in
    /// k_B T, from the first sample of the averaging window to the end.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub heat: Option<f64>,
    /// With `energy_balance`: shadow work per particle and time unit, in k_B T, over the same
    /// window (in the steady state about minus the heat).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shadow_work: Option<f64>,
}

impl RunResult {
    pub fn job(&self) -> Job {
        Job {
            scheme: self.scheme.clone(),
            dt: self.dt,
            seed: self.seed,
        }
    }
}

/// How a caller watches and stops runs: `stop` is checked between chunks of steps, `progress`
/// receives the number of steps just completed.
#[derive(Clone, Copy)]
pub struct Control<'a> {
    pub stop: &'a AtomicBool,
    pub progress: &'a (dyn Fn(u64) + Sync),
}

/// Run `job` on `scene`'s system, stepping with `scheme` (what `job.scheme` names). A blow-up
/// is a result with `stable = false`; only invalid input is an error.
pub fn run(
    scene: &Scene,
    job: &Job,
    scheme: &(dyn Scheme + Sync),
    control: Control,
) -> Result<RunResult, ParamError> {
    let (dt, seed) = (job.dt, job.seed);
    let mut sys = scene.system(dt, seed)?;
    sys.check_scheme(scheme)?;
    let steps = scene.steps(dt);
    let every = scene.sample_every(dt);
    let mut thermo_avg = ThermoAverages::new(steps, scene.average_fraction)?;
    let mut rdf = match &scene.rdf {
        Some(r) => Some(Rdf::new(&sys, r.r_max, r.bins)?),
        None => None,
    };
    let (rdf_stride, mut window_samples) = (scene.rdf_stride(dt), 0u64);
    let interval = every as f64 * dt;
    let mut vacf = match &scene.vacf {
        Some(v) => Some(Vacf::new(
            ((v.max_lag / interval).round() as usize).max(1),
            v.origin_every,
        )?),
        None => None,
    };
    let mut flows = FlowObservers::new(scene, &sys)?;
    let mut trajectory = match &scene.trajectory {
        Some(t) => Some(Recorder::start(t, dt, seed, scene.runs, &mut sys)?),
        None => None,
    };
    if scene.energy_balance {
        balance_defined(&sys, scheme)?;
    }
    // Started at the first sample of the averaging window: (balance, its step).
    let mut balance: Option<(EnergyBalance, u64)> = None;
    let (mut elapsed, mut forces, mut geometry) = (Duration::ZERO, 0, 0);
    let (mut error, mut interrupted) = (None, false);
    while sys.step() < steps {
        if control.stop.load(Ordering::Relaxed) {
            interrupted = true;
            break;
        }
        // Up to the next sample (a multiple of `every`), the end, or the trajectory's next stop.
        let next_sample = (sys.step() / every + 1) * every;
        let next_stop = trajectory
            .as_ref()
            .map_or(u64::MAX, |t| t.next_stop(sys.step()));
        let chunk = next_sample.min(steps).min(next_stop) - sys.step();
        let (before, from) = (sys.counters(), sys.step());
        let start = Instant::now();
        let outcome = sys.advance(scheme, chunk);
        elapsed += start.elapsed();
        let after = sys.counters();
        forces += after.force_evaluations - before.force_evaluations;
        geometry += after.pair_distance_evaluations - before.pair_distance_evaluations;
        (control.progress)(sys.step() - from);
        if let Err(blow_up) = outcome {
            error = Some(blow_up.to_string());
            break;
        }
        if let Some(t) = &mut trajectory {
            t.record_if_due(&mut sys)?;
        }
        let sampled = sys.step() % every == 0 || sys.step() == steps;
        if sampled && thermo_avg.wants(sys.step()) {
            thermo_avg.record(&thermo(&mut sys));
            if window_samples % rdf_stride == 0 {
                rdf.iter_mut().for_each(|r| r.record(&sys));
            }
            window_samples += 1;
            vacf.iter_mut().for_each(|v| v.record(&sys));
            flows.record(&mut sys);
            if scene.energy_balance && balance.is_none() {
                balance = Some((EnergyBalance::start(&mut sys, scheme)?, sys.step()));
            }
        }
    }
    let energies = balance.map(|(b, from)| (b.finish(&mut sys), sys.step() - from));
    let (viscosity, profile) = flows.finish(&mut sys);
    let done = sys.step();
    let per_step = |x: f64| (done > 0).then(|| x / done as f64);
    let s = thermo_avg.summary();
    let stable = error.is_none();
    let per_particle_time = |energy: f64, steps: u64| {
        let scale = sys.len() as f64 * steps as f64 * dt * scene.kbt;
        (stable && steps > 0 && energy.is_finite()).then(|| energy / scale)
    };
    let observed = |x: f64| (stable && s.samples > 0 && x.is_finite()).then_some(x);
    // Between walls the sums include frozen particles and the wall forces: T_C and the
    // periodic virial pressure do not mean what they mean in the bulk.
    let bulk = |x: f64| observed(x).filter(|_| scene.walls.is_none());
    Ok(RunResult {
        scheme: job.scheme.clone(),
        dt,
        seed,
        steps,
        completed_steps: done,
        stable,
        error,
        interrupted,
        samples: s.samples,
        kinetic_temperature: observed(s.kinetic_temperature),
        configurational_temperature: bulk(s.configurational_temperature),
        potential_energy: observed(s.potential_energy),
        pressure: bulk(s.pressure),
        ms_per_step: per_step(elapsed.as_secs_f64() * 1e3),
        force_evaluations_per_step: per_step(forces as f64),
        pair_distance_evaluations_per_step: per_step(geometry as f64),
        rdf: rdf
            .filter(|r| stable && r.samples() > 0)
            .map(|r| r.g().into_iter().map(|(r, g)| [r, g]).collect()),
        diffusion: vacf
            .filter(|_| stable && s.samples > 0)
            .map(|v| v.diffusion(interval))
            .filter(|d| d.is_finite()),
        viscosity: viscosity.map(|v| if stable { v } else { Viscosity::default() }),
        profile: profile.filter(|_| stable),
        heat: energies.and_then(|(b, steps)| per_particle_time(b.heat, steps)),
        shadow_work: energies.and_then(|(b, steps)| per_particle_time(b.shadow_work, steps)),
    })
}

/// A pool of `threads` rayon threads (0: one per core) for the core's pair loops.
pub(crate) fn pool(threads: usize) -> Result<rayon::ThreadPool, ParamError> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| ParamError::new("threads", threads, e.to_string()))
}

/// Run `jobs` with the schemes of `schemes` (by `job.scheme`), in order of the list, on
/// `scene.threads` workers (0: one per core): independent jobs in parallel, each on its
/// worker's own one-thread rayon pool, or a single job on a pool of all workers. Workers are
/// plain threads, not rayon workers: a rayon worker waiting for another pool would run other
/// jobs meanwhile, and their time would count as the waiting job's. Every result, also of
/// interrupted runs, goes to `on_result`; the first invalid input stops the others and is
/// returned.
pub fn run_parallel(
    scene: &Scene,
    jobs: &[Job],
    schemes: &HashMap<String, Box<dyn Scheme + Send + Sync>>,
    control: Control,
    on_result: &(dyn Fn(RunResult) + Sync),
) -> Result<(), ParamError> {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let threads = if scene.threads == 0 {
        cores
    } else {
        scene.threads
    };
    let (workers, inner) = match jobs.len() {
        1 => (1, threads),
        n => (threads.min(n), 1),
    };
    let next = AtomicUsize::new(0);
    let first_error = Mutex::new(None);
    let fail = |e: ParamError| {
        control.stop.store(true, Ordering::Relaxed);
        lock(&first_error).get_or_insert(e);
    };
    std::thread::scope(|s| {
        for _ in 0..workers {
            s.spawn(|| {
                let pool = match pool(inner) {
                    Ok(pool) => pool,
                    Err(e) => return fail(e),
                };
                while let Some(job) = jobs.get(next.fetch_add(1, Ordering::Relaxed)) {
                    if control.stop.load(Ordering::Relaxed) {
                        return;
                    }
                    let Some(scheme) = schemes.get(&job.scheme) else {
                        return fail(ParamError::new("scheme", &job.scheme, "was not resolved"));
                    };
                    match pool.install(|| run(scene, job, scheme, control)) {
                        Ok(r) => on_result(r),
                        Err(e) => return fail(e),
                    }
                }
            });
        }
    });
    match first_error.into_inner().unwrap_or_else(|e| e.into_inner()) {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

/// Lock `m`, also after a panic elsewhere (the data stay usable).
pub fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::RdfSpec;
    use dpd_schemes::registry::resolve;

    fn tiny() -> Scene {
        Scene {
            n: 100,
            time: 2.0,
            average_fraction: 0.5,
            rdf: Some(RdfSpec {
                r_max: 1.5,
                bins: 30,
                ..Default::default()
            }),
            ..Default::default()
        }
    }

    fn job(scheme: &str, dt: f64, seed: u64) -> Job {
        Job {
            scheme: scheme.into(),
            dt,
            seed,
        }
    }

    fn quiet(stop: &AtomicBool) -> Control<'_> {
        Control {
            stop,
            progress: &|_| {},
        }
    }

    #[test]
    fn a_run_samples_the_window_and_counts_evaluations() {
        let scene = tiny();
        let scheme = resolve("aboba").unwrap();
        let r = run(
            &scene,
            &job("aboba", 0.02, 3),
            &scheme,
            quiet(&AtomicBool::new(false)),
        )
        .unwrap();
        assert!(r.stable && !r.interrupted);
        assert_eq!((r.steps, r.completed_steps), (100, 100));
        // Samples every 5 steps in the last 50 steps: steps 50, 55, ..., 100.
        assert_eq!(r.samples, 11);
        assert_eq!(r.force_evaluations_per_step, Some(1.0));
        assert!(r.kinetic_temperature.unwrap() > 0.5 && r.rdf.unwrap().len() == 30);
    }

    #[test]
    fn g_of_r_is_recorded_every_interval_from_the_first_window_sample() {
        let scheme = resolve("aboba").unwrap();
        let g_of = |interval: Option<f64>| {
            let mut scene = tiny();
            scene.rdf.as_mut().unwrap().interval = interval;
            let r = run(
                &scene,
                &job("aboba", 0.02, 3),
                &scheme,
                quiet(&AtomicBool::new(false)),
            );
            r.unwrap().rdf.unwrap()
        };
        // Samples are 0.1 apart: an interval of 0.1 records every one, as the default does.
        assert_eq!(g_of(None), g_of(Some(0.1)));
        // An interval of 2 exceeds the window (steps 50 to 100): only step 50 is recorded.
        let mut sys = tiny().system(0.02, 3).unwrap();
        sys.advance(&scheme, 50).unwrap();
        let mut first = Rdf::new(&sys, 1.5, 30).unwrap();
        first.record(&sys);
        let expected: Vec<[f64; 2]> = first.g().into_iter().map(|(r, g)| [r, g]).collect();
        assert_eq!(g_of(Some(2.0)), expected);
        assert_ne!(g_of(Some(2.0)), g_of(None));
    }

    #[test]
    fn a_blow_up_is_a_result() {
        let scheme = resolve("vv").unwrap();
        let r = run(
            &tiny(),
            &job("vv", 2.0, 1),
            &scheme,
            quiet(&AtomicBool::new(false)),
        )
        .unwrap();
        assert!(!r.stable && r.error.as_deref().unwrap().contains("blow-up"));
        assert_eq!(r.configurational_temperature, None);
    }

    #[test]
    fn a_stopped_run_is_marked_interrupted() {
        let scheme = resolve("aboba").unwrap();
        let r = run(
            &tiny(),
            &job("aboba", 0.02, 1),
            &scheme,
            quiet(&AtomicBool::new(true)),
        )
        .unwrap();
        assert!(r.interrupted && r.completed_steps == 0 && r.samples == 0);
    }
}
