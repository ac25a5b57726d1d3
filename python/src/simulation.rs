//! `dpd.Simulation`: one scene's system stepped by one scheme, read and written as numpy
//! arrays, copied into snapshots, saved to checkpoints, recorded into trajectories.

use crate::keys::{os_error, scene_of};
use crate::measure::{self, sample_steps, Measurement, Samples};
use crate::topology::{self, by_id};
use crate::{invalid, to_python, wait, BlowUpError};
use dpd_core::observe::thermo;
use dpd_core::{AdvanceError, CheckpointError, ParamError, Scheme, System, Vec3};
use dpd_ir::lang::Options;
use dpd_measure::data_file::data_of;
use dpd_measure::observer::{Observer, Recorder};
use dpd_measure::scene::{Field, TrajectorySpec};
use dpd_measure::start::Origin;
use dpd_measure::Keys;
use dpd_measure::Scene;
use dpd_schemes::check::CheckError;
use dpd_schemes::registry::resolve_with;
use dpd_trajectory::TrajectoryError;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use pythonize::depythonize;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};

/// Steps between checks for Ctrl-C within `run` and `measure`.
const CHUNK: u64 = 50;

/// Simulation(*, allow_inconsistent=False, scene=None, scheme=None, dt=None, n=None, density=None, box=None, a=None, gamma=None, kbt=None, mass=None, weight_exponent=None, seed=None, threads=None, skin=None, shear_rate=None, body_force=None, walls=None, init=None, init_reset=None, trajectory=None, time=None, average_fraction=None, sample_interval=None, runs=None, energy_balance=None, like_neighbours=None, species=None, pairs=None, bond_types=None, angle_types=None, molecules=None, rdf=None, vacf=None, profile=None, sweep=None, description=None)
/// --
///
/// The initial state of a scene (uniform positions, Maxwell velocities, as the first run of
/// `dpd run`; or the frame of `init`) with its scheme. Every keyword is the scene key of the
/// same name (docs/scenes.md lists them; tables such as `walls` or `trajectory` take a dict of
/// their keys); `scene` names a TOML scene file whose keys they override. A scene with a
/// `trajectory` table records it during `run`, as `dpd run` does. Reduced DPD units.
/// Raises TypeError for an unknown keyword or a value of the wrong type, ValueError for an
/// invalid value.
#[pyclass(module = "dpd")]
pub struct Simulation {
    scene: Scene,
    system: System,
    scheme: Box<dyn Scheme + Send + Sync>,
    /// The core's pair loops run on `scene.run.threads` threads (0: one per core).
    pool: rayon::ThreadPool,
    /// Step and time of the system's step 0 (an `init` frame's, else 0); the time is shifted
    /// at every change of dt so that it runs on continuously.
    origin: Origin,
    recorder: Option<Recorder>,
    /// The samples of the last `measure` call, for `measure(accumulate=True)`; dropped when
    /// dt, the state or the particles change.
    samples: Option<Samples>,
}

/// A copy of a simulation's state (`Simulation.snapshot()`), restored bit for bit by
/// `Simulation.restore()`.
#[pyclass(module = "dpd", frozen)]
pub struct Snapshot {
    system: System,
    scheme: String,
    origin: Origin,
}

#[pymethods]
impl Snapshot {
    /// Step of the copied state.
    #[getter]
    fn step(&self) -> u64 {
        self.origin.step + self.system.step()
    }

    fn __repr__(&self) -> String {
        format!(
            "Snapshot(scheme={:?}, dt={}, step={})",
            self.scheme,
            self.system.dt(),
            self.step()
        )
    }
}

/// `rows` as an (N, 3) array.
fn array(py: Python<'_>, rows: Vec<Vec3>) -> Bound<'_, PyArray2<f64>> {
    let n = rows.len();
    let flat: Vec<f64> = rows.iter().flat_map(|v| [v.x, v.y, v.z]).collect();
    Array2::from_shape_vec((n, 3), flat)
        .expect("n rows of 3")
        .into_pyarray(py)
}

/// An (N, 3) array of floats from any array-like `value`, by particle id, as storage-ordered
/// vectors; `name` names it in errors.
fn rows_by_id(sys: &System, name: &str, value: &Bound<'_, PyAny>) -> PyResult<Vec<Vec3>> {
    let numpy = value.py().import("numpy")?;
    let a = numpy.call_method1("asarray", (value, "float64"))?;
    let a: PyReadonlyArrayDyn<f64> = a.extract()?;
    let n = sys.len();
    if a.shape() != [n, 3] {
        return Err(invalid(format!(
            "invalid {name}: shape {:?}; must be ({n}, 3), one row per particle",
            a.shape()
        )));
    }
    let a = a.as_array();
    if let Some(bad) = a.iter().find(|x| !x.is_finite()) {
        return Err(invalid(format!("invalid {name}: {bad}; must be finite")));
    }
    Ok(sys
        .ids()
        .iter()
        .map(|&id| {
            let i = id as usize;
            Vec3::new(a[[i, 0]], a[[i, 1]], a[[i, 2]])
        })
        .collect())
}

/// The scheme `name` resolves to, checked against the force groups of `sys`; or the
/// `ValueError` `dpd check` prints, or the one naming the force group.
fn scheme_of(
    name: &str,
    allow_inconsistent: bool,
    sys: &System,
) -> PyResult<Box<dyn Scheme + Send + Sync>> {
    let scheme = resolve_with(name, &Options { allow_inconsistent }).map_err(|reason| {
        invalid(CheckError {
            scheme: name.to_string(),
            reason,
        })
    })?;
    sys.check_scheme(scheme.as_ref()).map_err(invalid)?;
    Ok(scheme)
}

fn checkpoint_error(e: CheckpointError) -> PyErr {
    match &e {
        CheckpointError::Io { source, .. } => os_error(source, e.to_string()),
        _ => invalid(e),
    }
}

/// Steps between samples and what takes them, for `Simulation::advance`.
type Sampling<'a> = (u64, &'a mut (dyn FnMut(&mut System) + Send));

/// What stopped `run`: a blow-up (or a scheme the system cannot run), or a trajectory frame
/// that could not be written.
enum Stopped {
    Advance(AdvanceError),
    Write(ParamError),
}

#[pymethods]
impl Simulation {
    #[new]
    #[pyo3(signature = (*, allow_inconsistent=false, **scene), text_signature = "(*, allow_inconsistent=False, scene=None, scheme=None, dt=None, n=None, density=None, box=None, a=None, gamma=None, kbt=None, mass=None, weight_exponent=None, seed=None, threads=None, skin=None, shear_rate=None, body_force=None, walls=None, init=None, init_reset=None, trajectory=None, time=None, average_fraction=None, sample_interval=None, runs=None, energy_balance=None, like_neighbours=None, species=None, pairs=None, bond_types=None, angle_types=None, molecules=None, rdf=None, vacf=None, profile=None, sweep=None, description=None)")]
    fn new(allow_inconsistent: bool, scene: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let mut scene = scene_of(scene, &Keys::new())?;
        // The keyword and the scene key (of a scene file) mean the same.
        scene.run.allow_inconsistent |= allow_inconsistent;
        if let Some(file) = &scene.output.write_data {
            return Err(invalid(format!(
                "invalid write_data = {:?}: `dpd run` writes each run's last state there; from \
                 Python call sim.write_data(path) when the state is the one to write",
                file.display()
            )));
        }
        let run = &scene.run;
        let mut system = scene.system(run.dt, run.seed).map_err(invalid)?;
        let scheme = scheme_of(&run.scheme, run.allow_inconsistent, &system)?;
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(run.threads)
            .build()
            .map_err(|e| invalid(format!("invalid threads = {}: {e}", run.threads)))?;
        let origin = scene.origin(run.dt).map_err(invalid)?;
        let recorder = match &scene.output.trajectory {
            Some(spec) => Some(
                Recorder::start(
                    spec,
                    run.dt,
                    (run.seed, 1),
                    scene.trajectory_names(&system),
                    origin.clone(),
                    &mut system,
                )
                .map_err(invalid)?,
            ),
            None => None,
        };
        Ok(Simulation {
            scene,
            system,
            scheme,
            pool,
            origin,
            recorder,
            samples: None,
        })
    }

    /// run(steps)
    /// --
    ///
    /// Advance `steps` steps of dt with the GIL released, writing the trajectory's frames as
    /// they fall due. Raises BlowUpError (the state is the one before the failing step) or,
    /// on Ctrl-C, KeyboardInterrupt after the current chunk of steps.
    fn run(&mut self, py: Python<'_>, steps: i64) -> PyResult<()> {
        self.advance(py, steps, None)
    }

    /// measure(steps, *, every=None, blocks=10, rdf=None, vacf=None, profile=None, like_neighbours=None, accumulate=False)
    /// --
    ///
    /// Run `steps` steps as `run` does, sampling the state every `every` time units (default:
    /// the scene's sample_interval; rounded to whole steps), and return a Measurement: the
    /// means of k_B T_K, k_B T_C, the potential energy and the pressure with standard errors
    /// from `blocks` blocks of consecutive samples; with `rdf` or `vacf`, g(r) (and with
    /// several types g_ij(r)) and the velocity autocorrelation of the same samples; with
    /// `profile`, each type's slab densities; with `like_neighbours`, each type's fraction of
    /// like neighbours; with bonds, the mean bond length and the chains' <R_ee^2> and <R_g^2>.
    /// `rdf`, `vacf` and `profile` are the scene's tables of that name (None: the scene's, if
    /// it has one; True: on, with the scene's keys or the defaults; a dict: on, with those
    /// keys; False: off). The state before is not sampled. `accumulate=True` goes on with the
    /// samples of the previous measure call (its every and tables, which it then refuses) and
    /// returns the measurement of all of them, a running average; changing dt, the state or
    /// the particles between the calls ends the series.
    #[pyo3(signature = (
        steps, *, every=None, blocks=10, rdf=None, vacf=None, profile=None,
        like_neighbours=None, accumulate=false
    ))]
    #[allow(clippy::too_many_arguments)]
    fn measure(
        &mut self,
        py: Python<'_>,
        steps: i64,
        every: Option<f64>,
        blocks: usize,
        rdf: Option<Bound<'_, PyAny>>,
        vacf: Option<Bound<'_, PyAny>>,
        profile: Option<Bound<'_, PyAny>>,
        like_neighbours: Option<bool>,
        accumulate: bool,
    ) -> PyResult<Measurement> {
        let given = [
            every.is_some(),
            rdf.is_some(),
            vacf.is_some(),
            profile.is_some(),
        ];
        if accumulate && (given.into_iter().any(|g| g) || like_neighbours.is_some()) {
            return Err(PyTypeError::new_err(
                "measure(accumulate=True) goes on with the previous call's every, rdf, vacf, \
                 profile and like_neighbours: give none of them",
            ));
        }
        let mut samples =
            match self.samples.take() {
                Some(samples) if accumulate => samples,
                None if accumulate => return Err(invalid(
                    "measure(accumulate=True): no samples to go on from (no measure call since \
                     the simulation was made or its dt, state or particles changed)",
                )),
                _ => {
                    let dt = self.system.dt();
                    let every = sample_steps(every.unwrap_or(self.scene.run.sample_interval), dt)?;
                    let (tables, names) = (&self.scene.observe, self.types());
                    let observe = measure::observe(
                        tables,
                        rdf.as_ref(),
                        vacf.as_ref(),
                        profile.as_ref(),
                        like_neighbours,
                    )?;
                    Samples::new(&self.system, &observe, every, names).map_err(invalid)?
                }
            };
        let every = samples.every;
        let outcome = self.advance(py, steps, Some((every, &mut |sys| samples.record(sys))));
        let measurement = samples.finish(py, blocks);
        self.samples = Some(samples);
        outcome?;
        measurement
    }

    /// Positions, an (N, 3) array wrapped into the box, row i for particle i (the order in
    /// which the system was built, as in trajectories). Settable from any (N, 3) array-like,
    /// wrapped into the box.
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let s = &self.system;
        array(py, by_id(s, s.positions()))
    }

    #[setter]
    fn set_positions(&mut self, value: &Bound<'_, PyAny>) -> PyResult<()> {
        self.no_trajectory("set positions")?;
        let q = rows_by_id(&self.system, "positions", value)?;
        self.samples = None;
        self.system.set_positions(&q).map_err(invalid)
    }

    /// Velocities p / m, an (N, 3) array, row i for particle i. Settable from any (N, 3)
    /// array-like.
    #[getter]
    fn velocities<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let s = &self.system;
        let v: Vec<Vec3> = (s.momenta().iter().zip(s.masses()))
            .map(|(&p, &m)| p * (1.0 / m))
            .collect();
        array(py, by_id(s, &v))
    }

    #[setter]
    fn set_velocities(&mut self, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let v = rows_by_id(&self.system, "velocities", value)?;
        self.samples = None;
        let masses = self.system.masses().to_vec();
        for ((p, v), m) in self.system.momenta_mut().iter_mut().zip(v).zip(masses) {
            *p = v * m;
        }
        Ok(())
    }

    /// The type of each particle, an (N,) int array, row i for particle i: an index into
    /// `types`.
    #[getter]
    fn typeid<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        topology::typeid(py, &self.system)
    }

    /// The names of the particle types: the scene's species in their order, else A, B, ...
    #[getter]
    fn types(&self) -> Vec<String> {
        (self.scene).type_names(self.system.params().types())
    }

    /// The mass of each particle, an (N,) array, row i for particle i.
    #[getter]
    fn masses<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        by_id(&self.system, self.system.masses()).into_pyarray(py)
    }

    /// The bonds, a (B, 2) int array of particle ids (0 rows without bonds).
    #[getter]
    fn bonds<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<i64>> {
        topology::bonds(py, &self.system)
    }

    /// The type of each bond, a (B,) int array: an index into `bond_types`.
    #[getter]
    fn bond_typeid<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        topology::bonded_typeid(py, &self.system, false)
    }

    /// The names of the bond types: the scene's `[[bond_types]]`, else (a data file's) "1",
    /// "2", ...
    #[getter]
    fn bond_types(&self) -> Vec<String> {
        self.scene.bond_type_names(&self.system)
    }

    /// The angles, an (A, 3) int array of particle ids (i, j, k), j the vertex.
    #[getter]
    fn angles<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<i64>> {
        topology::angles(py, &self.system)
    }

    /// The type of each angle, an (A,) int array: an index into `angle_types`.
    #[getter]
    fn angle_typeid<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        topology::bonded_typeid(py, &self.system, true)
    }

    /// The names of the angle types: the scene's `[[angle_types]]`, else "1", "2", ...
    #[getter]
    fn angle_types(&self) -> Vec<String> {
        self.scene.angle_type_names(&self.system)
    }

    /// The linear chains the bonds make (molecules whose bonds form one open, unbranched
    /// path; others are left out): a list of int arrays, each the particle ids along one
    /// chain from its end with the smaller id. A scene's `[[molecules]]` are its chains.
    #[getter]
    fn chains<'py>(&self, py: Python<'py>) -> Vec<Bound<'py, PyArray1<i64>>> {
        topology::chains(py, &self.system)
    }

    /// Steps done (counted on from an `init` frame's step unless `init_reset`).
    #[getter]
    fn step(&self) -> u64 {
        self.origin.step + self.system.step()
    }

    /// Simulation time reached: the sum of the steps' dt (from an `init` frame's time).
    #[getter]
    fn time(&self) -> f64 {
        self.origin.time + self.system.step() as f64 * self.system.dt()
    }

    /// Time step; settable between runs (the time runs on continuously). Not while a
    /// trajectory is being written, whose frames are counted in steps of the dt it started at.
    #[getter]
    fn dt(&self) -> f64 {
        self.system.dt()
    }

    #[setter]
    fn set_dt(&mut self, dt: f64) -> PyResult<()> {
        self.no_trajectory("change dt")?;
        let (old, steps) = (self.system.dt(), self.system.step() as f64);
        self.system.set_dt(dt).map_err(invalid)?;
        self.samples = None;
        self.origin.time += steps * (old - dt);
        self.scene.run.dt = dt;
        Ok(())
    }

    /// The scheme, a registry name or a scheme string; settable between runs.
    #[getter]
    fn scheme(&self) -> String {
        self.scene.run.scheme.clone()
    }

    #[setter]
    fn set_scheme(&mut self, scheme: String) -> PyResult<()> {
        self.scheme = scheme_of(&scheme, self.scene.run.allow_inconsistent, &self.system)?;
        self.scene.run.scheme = scheme;
        Ok(())
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

    /// snapshot()
    /// --
    ///
    /// A copy of the whole state (positions, momenta, step, dt, scheme, the neighbour list
    /// and the caches the next step reads): `restore` continues from it bit for bit.
    fn snapshot(&self) -> Snapshot {
        Snapshot {
            system: self.system.clone(),
            scheme: self.scene.run.scheme.clone(),
            origin: self.origin.clone(),
        }
    }

    /// restore(snapshot)
    /// --
    ///
    /// Return to the state of `snapshot` (also its dt and scheme).
    fn restore(&mut self, snapshot: &Snapshot) -> PyResult<()> {
        self.no_trajectory("restore a snapshot")?;
        self.scheme = scheme_of(&snapshot.scheme, true, &snapshot.system)?;
        self.system = snapshot.system.clone();
        self.samples = None;
        self.origin = snapshot.origin.clone();
        self.scene.run.scheme = snapshot.scheme.clone();
        self.scene.run.dt = self.system.dt();
        Ok(())
    }

    /// save_checkpoint(path)
    /// --
    ///
    /// Write the state to a checkpoint file (the format of the `dpd` program's checkpoints,
    /// written atomically); `load_checkpoint` continues from it bit for bit, also in another
    /// process. Raises OSError when the file cannot be written.
    fn save_checkpoint(&self, path: PathBuf) -> PyResult<()> {
        self.system
            .save_checkpoint(&path, &self.scene.run.scheme)
            .map_err(checkpoint_error)
    }

    /// load_checkpoint(path)
    /// --
    ///
    /// Replace the state by the checkpoint's (its particles, dt and scheme; the time is
    /// step x dt of the checkpoint). Raises OSError for a file that cannot be read, ValueError
    /// for one that is not a valid checkpoint.
    fn load_checkpoint(&mut self, path: PathBuf) -> PyResult<()> {
        self.no_trajectory("load a checkpoint")?;
        let (system, name) = System::load_checkpoint(&path).map_err(checkpoint_error)?;
        self.scheme = scheme_of(&name, true, &system)?;
        self.system = system;
        self.samples = None;
        self.origin = Origin::default();
        self.scene.run.scheme = name;
        self.scene.run.dt = self.system.dt();
        self.scene.geometry.n = self.system.len();
        Ok(())
    }

    /// write_data(path)
    /// --
    ///
    /// Write the state as a LAMMPS data file, as `dpd run --write-data` writes a run's last
    /// one (docs/systems.md): type names, masses, positions and velocities by atom id = particle
    /// id + 1, the pair coefficients, and the bonds and angles with their coefficients.
    /// `Simulation(init=path)` (with the same species) and LAMMPS's `read_data` start from it.
    /// Raises ValueError with walls or shear (a data file holds a periodic box), OSError when
    /// the file cannot be written.
    fn write_data(&self, path: PathBuf) -> PyResult<()> {
        let sys = &self.system;
        if sys.walls().is_some() || sys.shear().is_some() {
            return Err(invalid(format!(
                "cannot write_data {}: a data file holds a periodic box, not walls or a shear \
                 rate",
                path.display()
            )));
        }
        let title = format!("dpd from Python, step {}, dt = {}", self.step(), sys.dt());
        let data = data_of(sys, &self.types(), &title).map_err(invalid)?;
        data.write(&path).map_err(|e| match &e {
            TrajectoryError::Io { source, .. } => os_error(source, e.to_string()),
            _ => invalid(e),
        })
    }

    /// trajectory(file, every=None, fields=None)
    /// --
    ///
    /// Write a frame of the current state to `file` (.gsd, .xyz, .lammpstrj or .dump) now and
    /// every `every` time units of the following runs, as `dpd run --trajectory` does;
    /// `fields` is a list of "velocity", "mass", "image", "observables" (default: all;
    /// images count from now). `trajectory(None)` closes the file.
    #[pyo3(signature = (file, every=None, fields=None))]
    fn trajectory(
        &mut self,
        file: Option<PathBuf>,
        every: Option<f64>,
        fields: Option<Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        self.recorder = None;
        let Some(file) = file else {
            return Ok(());
        };
        let every = every
            .ok_or_else(|| PyTypeError::new_err("trajectory(file, every): every is missing"))?;
        let fields: Option<Vec<Field>> = fields
            .map(|f| depythonize(&f))
            .transpose()
            .map_err(|e| invalid(format!("invalid fields: {e}")))?;
        let spec = TrajectorySpec {
            fields,
            ..TrajectorySpec::new(file, every)
        };
        spec.validate().map_err(invalid)?;
        let origin = Origin {
            images: None,
            ..self.origin.clone()
        };
        let dt = self.system.dt();
        self.recorder = Some(
            Recorder::start(
                &spec,
                dt,
                (self.scene.run.seed, 1),
                self.scene.trajectory_names(&self.system),
                origin,
                &mut self.system,
            )
            .map_err(invalid)?,
        );
        Ok(())
    }

    /// Refused: a Simulation holds a thread pool and open files. `snapshot()` copies the
    /// state within a process, `save_checkpoint(path)` across processes.
    fn __reduce__(&self) -> PyResult<PyObject> {
        Err(PyTypeError::new_err(
            "cannot pickle a dpd.Simulation: use snapshot() to copy its state within a \
             process, save_checkpoint(path) and load_checkpoint(path) across processes",
        ))
    }

    fn __repr__(&self) -> String {
        format!(
            "Simulation(scheme={:?}, dt={}, n={}, step={})",
            self.scene.run.scheme,
            self.system.dt(),
            self.system.len(),
            self.step()
        )
    }
}

impl Simulation {
    /// Advance `steps` steps with the GIL released (Ctrl-C stops them after the current
    /// chunk), writing the trajectory's frames as they fall due and handing the state to
    /// the sampler of `sampling` after each of its number of steps.
    fn advance(
        &mut self,
        py: Python<'_>,
        steps: i64,
        sampling: Option<Sampling<'_>>,
    ) -> PyResult<()> {
        let steps = u64::try_from(steps)
            .map_err(|_| invalid(format!("invalid steps = {steps}: must be >= 0")))?;
        let stop = AtomicBool::new(false);
        let (system, scheme, pool) = (&mut self.system, &self.scheme, &self.pool);
        let recorder = &mut self.recorder;
        let outcome = wait::interruptible(py, &stop, || {
            pool.install(|| {
                let (start, end) = (system.step(), system.step() + steps);
                let mut sampling = sampling;
                while system.step() < end && !stop.load(Ordering::Relaxed) {
                    let done = system.step() - start;
                    let frame = recorder
                        .as_ref()
                        .map_or(u64::MAX, |r| r.next_stop(system.step()));
                    let sample = sampling
                        .as_ref()
                        .map_or(u64::MAX, |(every, _)| start + (done / every + 1) * every);
                    let chunk = (end.min(frame).min(sample) - system.step()).min(CHUNK);
                    system
                        .advance(scheme.as_ref(), chunk)
                        .map_err(Stopped::Advance)?;
                    if let Some(r) = recorder.as_mut() {
                        r.after_steps(system).map_err(Stopped::Write)?;
                    }
                    if let Some((every, sample)) = sampling.as_mut() {
                        if (system.step() - start).is_multiple_of(*every) {
                            sample(system);
                        }
                    }
                }
                Ok(())
            })
        })?;
        outcome.map_err(|e| match e {
            Stopped::Advance(AdvanceError::BlowUp(e)) => BlowUpError::new_err(e.to_string()),
            Stopped::Advance(AdvanceError::Scheme(e)) => invalid(e),
            Stopped::Write(e) => invalid(e),
        })
    }

    /// Refuse `what` while a trajectory is being written: its frames count steps of one dt
    /// and follow the particles' images from step to step.
    fn no_trajectory(&self, what: &str) -> PyResult<()> {
        match &self.recorder {
            Some(_) => Err(PyValueError::new_err(format!(
                "cannot {what} while a trajectory is being written (its frames count steps of \
                 one dt and follow each particle's images): close it first with \
                 sim.trajectory(None)"
            ))),
            None => Ok(()),
        }
    }
}
