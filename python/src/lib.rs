//! The Python module `dpd`: the order analysis, the registry, a steppable simulation, the
//! dt sweep and the KL estimate, as thin wrappers over the crates the `dpd` program uses.
//! Results are the same JSON values the program prints, converted to Python objects. Errors are
//! of the Python kind: a wrong type or an unknown keyword is a `TypeError`, an invalid value a
//! `ValueError` with the program's message, a file that cannot be read or written an `OSError`,
//! a blow-up `dpd.BlowUpError`.

mod keys;
mod measure;
mod simulation;
mod topology;
mod typed;
mod wait;

use dpd_ir::lang::split_schemes;
use dpd_measure::kl::{estimate, KlError, KlSpec};
use dpd_measure::sweep::{load_finished, run_sweep, write_finished, Hooks};
use dpd_measure::{Control, Keys, Observable, SweepResults};
use dpd_schemes::check::{check as check_scheme, CheckError};
use dpd_schemes::registry::resolve;
use dpd_schemes::registry::{entries, Row};
use keys::{os_error, scene_of};
use pyo3::exceptions::{PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use pythonize::{depythonize, pythonize};
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;
use std::sync::Mutex;

pyo3::create_exception!(
    dpd,
    BlowUpError,
    PyRuntimeError,
    "A step produced a non-finite value or moved a particle too far; the simulation stays \
     in the state before that step."
);

/// `ValueError` carrying `e`'s message.
fn invalid(e: impl ToString) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// `value` as Python objects (dicts, lists, floats, None), as `serde_json` would print it.
fn to_python<T: serde::Serialize>(py: Python<'_>, value: &T) -> PyResult<PyObject> {
    Ok(pythonize(py, value)
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))?
        .unbind())
}

/// check(scheme)
/// --
///
/// The order analysis of a registry name or a scheme string: the dict of `dpd check --json`.
#[pyfunction]
fn check(py: Python<'_>, scheme: &str) -> PyResult<PyObject> {
    to_python(py, &check_scheme(scheme).map_err(invalid)?)
}

/// schemes()
/// --
///
/// The registry of named schemes: the list of `dpd schemes --json`.
#[pyfunction]
fn schemes(py: Python<'_>) -> PyResult<PyObject> {
    let rows: Vec<&Row> = entries().iter().map(|e| e.row()).collect();
    to_python(py, &rows)
}

/// sweep(*, schemes=None, dt_min=None, dt_max=None, dt_factor=None, reference=None, observable=None, json=None, fresh=False, scene=None, **keys)
/// --
///
/// Schemes over a geometric range of dt, as `dpd sweep`: returns the results file's content
/// (scene, points, rows, baseline, summary, complete) as Python objects. `schemes` is a list of
/// registry names or scheme strings, or one string split at its top-level commas as
/// `--schemes` is. `json` names a results file written after every finished point and read
/// back to resume (unless `fresh`); it is written once before the runs start, so a path that
/// cannot be written raises `OSError` at once. The other keywords are scene keys, as for
/// `Simulation`. The GIL is released while the runs go on; Ctrl-C stops them and raises
/// `KeyboardInterrupt` (the finished points are in `json`).
#[pyfunction]
#[pyo3(signature = (
    *, schemes=None, dt_min=None, dt_max=None, dt_factor=None, reference=None,
    observable=None, json=None, fresh=false, **scene
), text_signature = "(*, schemes=None, dt_min=None, dt_max=None, dt_factor=None, reference=None, observable=None, json=None, fresh=False, scene=None, **keys)")]
#[allow(clippy::too_many_arguments)]
fn sweep(
    py: Python<'_>,
    schemes: Option<Bound<'_, PyAny>>,
    dt_min: Option<f64>,
    dt_max: Option<f64>,
    dt_factor: Option<f64>,
    reference: Option<String>,
    observable: Option<Bound<'_, PyAny>>,
    json: Option<PathBuf>,
    fresh: bool,
    scene: Option<&Bound<'_, PyDict>>,
) -> PyResult<PyObject> {
    let observable: Option<Observable> = observable
        .map(|o| depythonize(&o))
        .transpose()
        .map_err(|e| invalid(format!("observable: {e}")))?;
    let schemes = schemes.map(|s| scheme_names(&s)).transpose()?;
    let mut table = Keys::new();
    let mut set = |key: &str, value: Option<toml::Value>| {
        if let Some(v) = value {
            table.insert(key.into(), v);
        }
    };
    set("schemes", schemes.map(|s| s.into()));
    set("dt_min", dt_min.map(toml::Value::from));
    set("dt_max", dt_max.map(toml::Value::from));
    set("dt_factor", dt_factor.map(toml::Value::from));
    set("reference", reference.map(toml::Value::from));
    set("observable", observable.map(|o| o.name().into()));
    let sweep_keys = Keys::from_iter([("sweep".to_string(), toml::Value::Table(table))]);
    let scene = scene_of(scene, &sweep_keys)?;
    let finished = match &json {
        Some(path) if !fresh => load_finished(path, &scene).map_err(invalid)?,
        _ => Vec::new(),
    };
    let cannot_write = |path: &PathBuf, e: &std::io::Error| {
        os_error(e, format!("cannot write {}: {e}", path.display()))
    };
    if let Some(path) = &json {
        write_finished(path, &scene, &finished).map_err(|e| cannot_write(path, &e))?;
    }
    let write_error = Mutex::new(None);
    let save = |r: &SweepResults| {
        if let Some(path) = &json {
            if let Err(e) = r.write_json(path) {
                let mut first = write_error.lock().unwrap_or_else(|e| e.into_inner());
                first.get_or_insert(cannot_write(path, &e));
            }
        }
    };
    let stop = AtomicBool::new(false);
    let hooks = Hooks {
        control: Control {
            stop: &stop,
            progress: &|_| {},
        },
        on_point: &save,
    };
    let results =
        wait::interruptible(py, &stop, || run_sweep(&scene, finished, hooks))?.map_err(invalid)?;
    if let Some(e) = write_error.into_inner().unwrap_or_else(|e| e.into_inner()) {
        return Err(e);
    }
    to_python(py, &results)
}

/// The schemes of `sweep(schemes=...)`: a list of strings, or one string split as
/// `--schemes` is.
fn scheme_names(schemes: &Bound<'_, PyAny>) -> PyResult<Vec<String>> {
    if schemes.is_instance_of::<PyString>() {
        let text: String = schemes.extract()?;
        return split_schemes(&text).map_err(|e| invalid(format!("invalid schemes: {e}")));
    }
    schemes.extract().map_err(|_| {
        PyTypeError::new_err(format!(
            "schemes: expected a str or a list of str, got {}",
            schemes
                .get_type()
                .name()
                .map_or("?".into(), |n| n.to_string())
        ))
    })
}

/// kl(scheme, *, samples=200, protocol_time=2.0, sweeps_between=2, scene=None, **keys)
/// --
///
/// The KL divergence between the configurations `scheme` samples at the scene's dt and
/// exp(-U / k_B T), estimated from shadow work as `dpd kl` does: the dict of
/// `dpd kl --json` (kl_divergence, kl_error, protocol_steps, samples, ...). Raises
/// ValueError for a scheme or scene the estimate does not apply to, BlowUpError when a
/// protocol blows up. The GIL is released meanwhile; Ctrl-C raises KeyboardInterrupt.
#[pyfunction]
#[pyo3(signature = (scheme, *, samples=None, protocol_time=None, sweeps_between=None, **scene))]
fn kl(
    py: Python<'_>,
    scheme: &str,
    samples: Option<u64>,
    protocol_time: Option<f64>,
    sweeps_between: Option<u64>,
    scene: Option<&Bound<'_, PyDict>>,
) -> PyResult<PyObject> {
    let scene = scene_of(scene, &Keys::new())?;
    let defaults = KlSpec::default();
    let spec = KlSpec {
        samples: samples.unwrap_or(defaults.samples),
        protocol_time: protocol_time.unwrap_or(defaults.protocol_time),
        sweeps_between: sweeps_between.unwrap_or(defaults.sweeps_between),
        ..defaults
    };
    let scheme = resolve(scheme).map_err(|reason| {
        invalid(CheckError {
            scheme: scheme.to_string(),
            reason,
        })
    })?;
    let stop = AtomicBool::new(false);
    let control = Control {
        stop: &stop,
        progress: &|_| {},
    };
    let result = wait::interruptible(py, &stop, || {
        estimate(&scene, scheme.as_ref(), scene.run.dt, &spec, control)
    })?;
    match result {
        Ok(r) => to_python(py, &r),
        Err(KlError::BlowUp(b)) => Err(BlowUpError::new_err(b.to_string())),
        Err(e) => Err(invalid(e)),
    }
}

/// Compose, check and run splitting integrators for dissipative particle dynamics.
#[pymodule]
#[pyo3(name = "dpd")]
fn dpd_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(check, m)?)?;
    m.add_function(wrap_pyfunction!(schemes, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(kl, m)?)?;
    m.add_class::<simulation::Simulation>()?;
    m.add_class::<simulation::Snapshot>()?;
    m.add_class::<measure::Measurement>()?;
    m.add_class::<measure::Estimate>()?;
    m.add("BlowUpError", m.py().get_type::<BlowUpError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
