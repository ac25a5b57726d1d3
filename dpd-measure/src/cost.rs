//! The cost per step of the schemes of a sweep, measured apart from its runs so that the
//! efficiency does not follow the machine's load.
//!
//! The runs of a sweep share the cores with one another and with whatever else the machine
//! does, so the milliseconds per step they record vary with the load while they ran (one
//! scheme's points may run while the machine is idle, another's while it is busy: the main job
//! once printed ABOBA's efficiency as 5.07 where an idle machine gives 1.9). After the runs,
//! each scheme steps a copy of the same start on one thread, the schemes taking turns window by
//! window, and its cost is the shortest window: a window that another process interrupted only
//! takes longer, so the minimum over many short windows is the cost of an uninterrupted step,
//! and the turns expose every scheme to the same load.

use crate::runner::{pool, Control};
use crate::scene::Scene;
use dpd_core::{ParamError, Scheme};
use serde::{Deserialize, Serialize};
use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};

/// Steps per timed window: about a millisecond at N = 500, short next to the time slices the
/// scheduler gives a process that shares a core.
pub const WINDOW_STEPS: u64 = 10;
/// Fewest windows per scheme.
pub const MIN_WINDOWS: u64 = 20;
/// Most windows per scheme.
pub const MAX_WINDOWS: u64 = 400;
/// Windows are timed until every scheme has [`MIN_WINDOWS`] and the timing has lasted this
/// long (or [`MAX_WINDOWS`] are reached).
pub const BUDGET: Duration = Duration::from_secs(1);

/// The cost per step of each scheme and how it was measured.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Cost {
    /// The time step of the timed steps (the sweep's smallest).
    pub dt: f64,
    pub window_steps: u64,
    /// Windows timed per scheme.
    pub windows: u64,
    /// Per scheme: milliseconds per step, the shortest window's (`None` when the scheme blew
    /// up while timed).
    pub ms_per_step: Vec<(String, Option<f64>)>,
}

impl Cost {
    /// The cost per step of `scheme`, if measured.
    pub fn of(&self, scheme: &str) -> Option<f64> {
        self.ms_per_step
            .iter()
            .find(|(s, _)| s == scheme)
            .and_then(|(_, ms)| *ms)
    }

    /// How the cost was measured, for a table's footer.
    pub fn describe(&self) -> String {
        format!(
            "ms/step: the shortest of {} windows of {} steps per scheme, timed on one thread \
             after the runs, the schemes taking turns, at dt = {}",
            self.windows, self.window_steps, self.dt
        )
    }
}

/// Time `schemes` (name and scheme) on `scene`'s start at `dt`; `None` when `control` stops it.
pub fn measure(
    scene: &Scene,
    schemes: &[(&str, &(dyn Scheme + Sync))],
    dt: f64,
    control: Control,
) -> Result<Option<Cost>, ParamError> {
    let start = scene.system(dt, scene.run.seed)?;
    let mut systems: Vec<_> = schemes.iter().map(|_| Some(start.clone())).collect();
    let mut best = vec![f64::INFINITY; schemes.len()];
    let began = Instant::now();
    let mut windows = 0;
    // The runs of a sweep step on one thread each; so do these.
    let timed = pool(1)?.install(|| {
        // One untimed window each first: caches and branch predictors warm.
        for round in 0..=MAX_WINDOWS {
            if control.stop.load(Ordering::Relaxed) {
                return false;
            }
            let enough = windows >= MIN_WINDOWS && began.elapsed() >= BUDGET;
            if enough || windows == MAX_WINDOWS {
                return true;
            }
            // Each round starts with another scheme, so none always follows the same one.
            for k in 0..schemes.len() {
                let i = (k + round as usize) % schemes.len();
                let Some(sys) = &mut systems[i] else {
                    continue;
                };
                let t = Instant::now();
                let outcome = sys.advance(schemes[i].1, WINDOW_STEPS);
                let ms = t.elapsed().as_secs_f64() * 1e3 / WINDOW_STEPS as f64;
                match outcome {
                    Ok(()) if round > 0 => best[i] = best[i].min(ms),
                    Ok(()) => {}
                    Err(_) => systems[i] = None,
                }
            }
            if round > 0 {
                windows += 1;
            }
        }
        true
    });
    Ok(timed.then(|| Cost {
        dt,
        window_steps: WINDOW_STEPS,
        windows,
        ms_per_step: schemes
            .iter()
            .zip(&systems)
            .zip(&best)
            .map(|((s, sys), &ms)| (s.0.to_string(), sys.as_ref().map(|_| ms)))
            .collect(),
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use dpd_schemes::registry::resolve;
    use std::sync::atomic::AtomicBool;

    /// Every scheme gets the same number of windows; a scheme that blows up has no cost; a
    /// stop request leaves no measurement.
    #[test]
    fn every_scheme_is_timed_in_turn_and_a_blow_up_has_no_cost() {
        let mut scene = Scene::default();
        scene.geometry.n = 100;
        let (vv, aboba) = (resolve("vv").unwrap(), resolve("aboba").unwrap());
        let stop = AtomicBool::new(false);
        let control = Control {
            stop: &stop,
            progress: &|_| {},
        };
        let schemes: [(&str, &(dyn Scheme + Sync)); 2] =
            [("vv", vv.as_ref()), ("aboba", aboba.as_ref())];
        let cost = measure(&scene, &schemes, 0.02, control).unwrap().unwrap();
        assert!((MIN_WINDOWS..=MAX_WINDOWS).contains(&cost.windows));
        let (a, b) = (cost.of("vv").unwrap(), cost.of("aboba").unwrap());
        assert!(
            a > 0.0 && b > 0.0 && a.is_finite() && b.is_finite(),
            "{cost:?}"
        );
        // At dt = 2 velocity Verlet blows up in its first window.
        let blown = measure(&scene, &schemes[..1], 2.0, control)
            .unwrap()
            .unwrap();
        assert_eq!(blown.of("vv"), None);
        stop.store(true, Ordering::Relaxed);
        assert_eq!(measure(&scene, &schemes, 0.02, control).unwrap(), None);
    }
}
