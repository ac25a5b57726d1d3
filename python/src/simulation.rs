//! `dpd.Simulation`: one scene's system stepped by one scheme, read back as numpy arrays and
//! observables.

use crate::{invalid, to_python, wait, BlowUpError};
use dpd_core::observe::thermo;
use dpd_core::{AdvanceError, Scheme, System};
use dpd_measure::Scene;
use dpd_schemes::check::CheckError;
use dpd_schemes::registry::resolve;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::sync::atomic::{AtomicBool, Ordering};

/// Steps between checks for Ctrl-C within `run`.
const CHUNK: u64 = 50;

/// Simulation(**scene)
/// --
///
/// The initial state of a scene (uniform positions, Maxwell velocities, as the first run of
/// `dpd run`) with its scheme. Keywords are the scene keys of `dpd run`'s flags (scheme, dt,
/// n, gamma, seed, density, a, kbt, mass, weight_exponent, threads, shear_rate, ...);
/// `scene` names a TOML scene file whose keys they override. Reduced DPD units.
#[pyclass(module = "dpd")]
pub struct Simulation {
    scene: Scene,
    system: System,
    scheme: Box<dyn Scheme + Send + Sync>,
    /// The core's pair loops run on `scene.threads` threads (0: one per core).
    pool: rayon::ThreadPool,
}

/// `rows` as an (N, 3) array.
fn array<'py>(
    py: Python<'py>,
    rows: impl ExactSizeIterator<Item = [f64; 3]>,
) -> Bound<'py, PyArray2<f64>> {
    let n = rows.len();
    let flat: Vec<f64> = rows.flatten().collect();
    Array2::from_shape_vec((n, 3), flat)
        .expect("n rows of 3")
        .into_pyarray(py)
}

#[pymethods]
impl Simulation {
    #[new]
    #[pyo3(signature = (**scene))]
    fn new(scene: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let scene = crate::scene_of(scene, &Default::default())?;
        let run = &scene.run;
        let scheme = resolve(&run.scheme).map_err(|reason| {
            invalid(CheckError {
                scheme: run.scheme.clone(),
                reason,
            })
        })?;
        let system = scene.system(run.dt, run.seed).map_err(invalid)?;
        system.check_scheme(scheme.as_ref()).map_err(invalid)?;
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(run.threads)
            .build()
            .map_err(|e| invalid(format!("invalid threads = {}: {e}", run.threads)))?;
        Ok(Simulation {
            scene,
            system,
            scheme,
            pool,
        })
    }

    /// run(steps)
    /// --
    ///
    /// Advance `steps` steps of dt with the GIL released. Raises BlowUpError (the state is
    /// the one before the failing step) or, on Ctrl-C, KeyboardInterrupt after the current
    /// chunk of steps.
    fn run(&mut self, py: Python<'_>, steps: u64) -> PyResult<()> {
        let stop = AtomicBool::new(false);
        let (system, scheme, pool) = (&mut self.system, &self.scheme, &self.pool);
        let outcome = wait::interruptible(py, &stop, || {
            pool.install(|| {
                let mut left = steps;
                while left > 0 && !stop.load(Ordering::Relaxed) {
                    let chunk = left.min(CHUNK);
                    system.advance(scheme.as_ref(), chunk)?;
                    left -= chunk;
                }
                Ok::<(), AdvanceError>(())
            })
        })?;
        outcome.map_err(|e| match e {
            AdvanceError::Scheme(e) => invalid(e),
            AdvanceError::BlowUp(e) => BlowUpError::new_err(e.to_string()),
        })
    }

    /// Positions, an (N, 3) array wrapped into the box.
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        array(py, self.system.positions().iter().map(|q| [q.x, q.y, q.z]))
    }

    /// Velocities p / m, an (N, 3) array.
    #[getter]
    fn velocities<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let s = &self.system;
        let v = s
            .momenta()
            .iter()
            .zip(s.masses())
            .map(|(p, m)| (p / *m).into());
        array(py, v)
    }

    /// Steps done.
    #[getter]
    fn step(&self) -> u64 {
        self.system.step()
    }

    /// Time reached, step x dt.
    #[getter]
    fn time(&self) -> f64 {
        self.system.step() as f64 * self.system.dt()
    }

    /// Box edges [L_x, L_y, L_z].
    #[getter]
    fn box_lengths(&self) -> [f64; 3] {
        self.system.boundary().lengths().into()
    }

    /// The effective scene, as the dict of the `scene` field of `dpd run --json`.
    #[getter]
    fn scene(&self, py: Python<'_>) -> PyResult<PyObject> {
        to_python(py, &self.scene)
    }

    /// observables()
    /// --
    ///
    /// The instantaneous observables of the current state: kinetic_temperature (k_B T_K),
    /// configurational_temperature (k_B T_C = config_numerator / config_denominator; average
    /// numerator and denominator separately), potential_energy (per particle), pressure
    /// (virial), step, time.
    fn observables(&mut self, py: Python<'_>) -> PyResult<PyObject> {
        let (system, pool) = (&mut self.system, &self.pool);
        let t = py.allow_threads(|| pool.install(|| thermo(system)));
        let d = to_python(py, &t)?;
        let d = d.bind(py).downcast::<PyDict>()?.clone();
        d.set_item(
            "configurational_temperature",
            t.configurational_temperature(),
        )?;
        d.set_item("step", self.step())?;
        d.set_item("time", self.time())?;
        Ok(d.into_any().unbind())
    }

    fn __repr__(&self) -> String {
        format!(
            "Simulation(scheme={:?}, dt={}, n={}, step={})",
            self.scene.run.scheme,
            self.scene.run.dt,
            self.system.len(),
            self.system.step()
        )
    }
}
