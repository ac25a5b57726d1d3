//! One run: a scene's system advanced with one scheme at one time step, sampled by its
//! observers (`crate::observer`) at the end of full steps, the integration timed on its own.

use crate::observer::{self, End, Setup};
use crate::result::Job;
use crate::result::RunResult;
use crate::scene::Scene;
use dpd_core::observe::ThermoAverages;
use dpd_core::{ParamError, Scheme};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};

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
    let steps = scene.run.steps(dt);
    let every = scene.run.sample_every(dt);
    let window = ThermoAverages::new(steps, scene.run.average_fraction)?;
    let setup = Setup {
        scene,
        scheme,
        dt,
        seed,
        steps,
        every,
    };
    let mut observers = observer::for_run(&setup, &mut sys)?;
    let (mut elapsed, mut forces, mut geometry) = (Duration::ZERO, 0, 0);
    let (mut error, mut interrupted, mut samples) = (None, false, 0u64);
    while sys.step() < steps {
        if control.stop.load(Ordering::Relaxed) {
            interrupted = true;
            break;
        }
        // Up to the next sample (a multiple of `every`), the end, or an observer's next stop.
        let next_sample = (sys.step() / every + 1) * every;
        let next_stop = observers.iter().map(|o| o.next_stop(sys.step())).min();
        let chunk = next_sample.min(steps).min(next_stop.unwrap_or(u64::MAX)) - sys.step();
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
        for o in &mut observers {
            o.after_steps(&mut sys)?;
        }
        let sampled = sys.step() % every == 0 || sys.step() == steps;
        if sampled && window.wants(sys.step()) {
            for o in &mut observers {
                o.sample(&mut sys, samples)?;
            }
            samples += 1;
        }
    }
    let done = sys.step();
    let per_step = |x: f64| (done > 0).then(|| x / done as f64);
    let mut result = RunResult {
        scheme: job.scheme.clone(),
        dt,
        seed,
        steps,
        completed_steps: done,
        stable: error.is_none(),
        error,
        interrupted,
        ms_per_step: per_step(elapsed.as_secs_f64() * 1e3),
        force_evaluations_per_step: per_step(forces as f64),
        pair_distance_evaluations_per_step: per_step(geometry as f64),
        acceptance: sys.acceptance().rate(),
        ..RunResult::default()
    };
    let end = End {
        stable: result.stable,
    };
    for o in observers {
        o.finish(&mut sys, &end, &mut result);
    }
    Ok(result)
}

/// A pool of `threads` rayon threads (0: one per core) for the core's pair loops.
pub(crate) fn pool(threads: usize) -> Result<rayon::ThreadPool, ParamError> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| ParamError::new("threads", threads, e.to_string()))
}

/// Lock `m`, also after a panic elsewhere (the data stay usable).
pub fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::RdfSpec;
    use dpd_core::observe::Rdf;
    use dpd_schemes::registry::resolve;

    fn tiny() -> Scene {
        let mut scene = Scene::default();
        scene.geometry.n = 100;
        scene.run.time = 2.0;
        scene.run.average_fraction = 0.5;
        scene.observe.rdf = Some(RdfSpec {
            r_max: 1.5,
            bins: 30,
            ..Default::default()
        });
        scene
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
            scene.observe.rdf.as_mut().unwrap().interval = interval;
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
    fn processing_reads_the_positional_observables_off_an_untouched_trajectory() {
        // Without and with a skin (the neighbour list kept between steps).
        for skin in [0.0, 0.3] {
            processing_keeps_the_trajectory(skin);
        }
    }

    fn processing_keeps_the_trajectory(skin: f64) {
        let scheme = resolve("aboba").unwrap();
        let run_with = |c: Option<f64>| {
            let mut scene = tiny();
            scene.geometry.skin = skin;
            if let Some(c) = c {
                scene.observe.processing = c;
            }
            let r = run(
                &scene,
                &job("aboba", 0.05, 3),
                &scheme,
                quiet(&AtomicBool::new(false)),
            );
            let r = r.unwrap();
            let t = r.kinetic_temperature.unwrap();
            let positional = [
                r.configurational_temperature,
                r.potential_energy,
                r.pressure,
            ];
            (t, positional.map(Option::unwrap))
        };
        let plain = run_with(None);
        // c = 0 is the unprocessed observable, bit for bit.
        assert_eq!(run_with(Some(0.0)), plain);
        // Processing measures on a copy: the trajectory, and so T_K, is the same to the bit.
        let (t, [tc, u, _]) = run_with(Some(0.5));
        assert_eq!(t, plain.0);
        // A step along the forces lowers T_C (on a harmonic mode by (1 - c omega2 dt^2)^2)
        // and the potential energy.
        assert!(tc < plain.1[0] && u < plain.1[1], "{tc} {u} {plain:?}");
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
