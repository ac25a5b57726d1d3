//! The output section: the scene's description and the files `dpd run` writes (a trajectory,
//! a data file of the last state).

use dpd_core::ParamError;
use dpd_trajectory::Format;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Keys `description`, `write_data` and table `[trajectory]`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Output {
    /// Free text shown in the header.
    pub description: String,
    pub trajectory: Option<TrajectorySpec>,
    /// Write each run's last state as a LAMMPS data file, `FILE.data` (with several runs,
    /// `<stem>-seed<seed>.data`).
    pub write_data: Option<PathBuf>,
}

/// What a trajectory holds besides positions, box, step and types.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Field {
    /// Velocities (momentum / mass), r_c per time unit.
    Velocity,
    /// Masses.
    Mass,
    /// Periodic images (crossings of each pair of box faces since the run's start; followed
    /// after every step, see `crate::images::Images`). Not under Lees-Edwards boundaries.
    Image,
    /// The frame's k_B T_K, T_C, potential energy per particle and virial pressure (GSD
    /// `log/...`, extended-XYZ comment keys; not in LAMMPS dumps).
    Observables,
}

/// The `[trajectory]` table: a frame every `every` time units into `file`, whose extension
/// chooses the format (`.gsd`, `.xyz`, `.lammpstrj`/`.dump`). With several runs, run k writes
/// `<stem>-seed<seed>.<ext>`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrajectorySpec {
    pub file: PathBuf,
    /// Time between frames (rounded to whole steps, at least 1); the first frame is the
    /// initial state.
    pub every: f64,
    /// Default (`None`): all of them, but images under Lees-Edwards boundaries.
    #[serde(default)]
    pub fields: Option<Vec<Field>>,
}

impl Output {
    pub fn validate(&self) -> Result<(), ParamError> {
        if let Some(file) = &self.write_data {
            if file.extension().is_none_or(|e| e != "data") {
                return Err(ParamError::new(
                    "write_data",
                    file.display(),
                    "must be a LAMMPS data file, FILE.data",
                ));
            }
        }
        match &self.trajectory {
            Some(t) => t.validate(),
            None => Ok(()),
        }
    }
}

impl TrajectorySpec {
    pub fn new(file: PathBuf, every: f64) -> TrajectorySpec {
        TrajectorySpec {
            file,
            every,
            fields: None,
        }
    }

    pub fn validate(&self) -> Result<(), ParamError> {
        let every = self.every;
        if !(every.is_finite() && every > 0.0) {
            return Err(ParamError::new(
                "trajectory.every",
                every,
                "must be finite and > 0",
            ));
        }
        Format::of(&self.file)
            .map(|_| ())
            .map_err(|e| ParamError::new("trajectory.file", self.file.display(), e.to_string()))
    }

    /// Steps between frames at `dt`.
    pub fn every_steps(&self, dt: f64) -> u64 {
        ((self.every / dt).round() as u64).max(1)
    }

    /// The file of the run with `seed`: see [`run_path`].
    pub fn path(&self, seed: u64, runs: u64) -> PathBuf {
        run_path(&self.file, seed, runs)
    }
}

/// The file of the run with `seed` of `runs`: `file` itself when the scene has one run, else
/// `<stem>-seed<seed>.<ext>`.
pub fn run_path(file: &Path, seed: u64, runs: u64) -> PathBuf {
    if runs <= 1 {
        return file.to_path_buf();
    }
    let stem = file.file_stem().unwrap_or_default().to_string_lossy();
    let ext = file.extension().unwrap_or_default().to_string_lossy();
    file.with_file_name(format!("{stem}-seed{seed}.{ext}"))
}
