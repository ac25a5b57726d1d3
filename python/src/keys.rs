//! Scene keys from Python keyword arguments. Each keyword is the scene key of the same name (a
//! table such as `rdf` takes a dict of its keys), merged over the scene file `scene` or the
//! default scene as the command line's flags are; a keyword given as `None` is not given. So
//! every key of a scene file is a keyword. Errors are of the Python kind: a keyword that is no
//! scene key, or a value of the wrong type, is a `TypeError`; a value the scene refuses is a
//! `ValueError`; a scene file that cannot be read, an `OSError` naming it.

use crate::invalid;
use dpd_measure::scene::section::merge;
use dpd_measure::{Keys, Scene, SceneError};
use pyo3::exceptions::{PyFileNotFoundError, PyOSError, PyPermissionError, PyTypeError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use pythonize::depythonize;
use std::path::PathBuf;

/// The scene of `kwargs` with `more` merged over it, validated.
pub fn scene_of(kwargs: Option<&Bound<'_, PyDict>>, more: &Keys) -> PyResult<Scene> {
    let mut file: Option<PathBuf> = None;
    let mut keys = Keys::new();
    for (key, value) in kwargs.into_iter().flat_map(|d| d.iter()) {
        let key: String = key.extract()?;
        if value.is_none() {
            continue;
        }
        if key == "scene" {
            let path = value
                .extract()
                .map_err(|_| PyTypeError::new_err("scene: expected a path (str or os.PathLike)"))?;
            file = Some(path);
            continue;
        }
        let value: toml::Value =
            depythonize(&value).map_err(|e| PyTypeError::new_err(format!("{key}: {e}")))?;
        keys.insert(key, value);
    }
    merge(&mut keys, more);
    Scene::resolve(file.as_deref(), &keys).map_err(scene_error)
}

/// A scene's error: `OSError` (`FileNotFoundError`, `PermissionError`) when its file cannot be
/// read, `TypeError` for an unknown key or a value of the wrong type, `ValueError` for a value
/// the scene refuses.
pub fn scene_error(e: SceneError) -> PyErr {
    match &e {
        SceneError::Io { source, .. } => os_error(source, e.to_string()),
        SceneError::Toml { path, message } => {
            let message = match path.as_str() {
                "(default)" => message.clone(),
                _ => e.to_string(),
            };
            if message.contains("invalid type") || message.contains("unknown field") {
                PyTypeError::new_err(message)
            } else {
                invalid(message)
            }
        }
        SceneError::Invalid(_) => invalid(e),
    }
}

/// The `OSError` subclass of `source`'s kind, with `message`.
pub fn os_error(source: &std::io::Error, message: String) -> PyErr {
    match source.kind() {
        std::io::ErrorKind::NotFound => PyFileNotFoundError::new_err(message),
        std::io::ErrorKind::PermissionDenied => PyPermissionError::new_err(message),
        _ => PyOSError::new_err(message),
    }
}
