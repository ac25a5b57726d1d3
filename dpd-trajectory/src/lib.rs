//! Trajectory files that the tools of the field read: GSD with the HOOMD schema (HOOMD-blue,
//! OVITO, freud, MDAnalysis), extended XYZ (ASE, OVITO) and LAMMPS dump text (LAMMPS, OVITO,
//! ASE). The format is chosen by the file's extension.
//!
//! Every frame is written whole or not at all as far as a reader can tell: a run killed
//! between frames, or while writing one, leaves a file with every finished frame (see each
//! writer for how). Units are the simulation's reduced units (lengths in r_c, times in the
//! reduced time unit, masses in the particle mass unit).
//!
//! No GSD crate exists on crates.io, and the `chemfiles` crate builds the C++ chemfiles library
//! with CMake (absent from the project's machines) for every clean CI build; the GSD file layer
//! is a short documented binary format, so [`gsd`] writes and reads it directly.

pub mod gsd;
pub mod lammps_data;
mod text;

use std::path::{Path, PathBuf};
use thiserror::Error;

/// One configuration of a periodic orthorhombic box. Positions are wrapped into
/// `[0, L)` per axis.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Frame {
    /// Time step number.
    pub step: u64,
    /// Simulation time of this frame, in reduced time units (GSD `log/time`, the extended XYZ's
    /// `time=`; a LAMMPS dump has the step only).
    pub time: f64,
    /// The time step the run used (GSD `log/dt`, the extended XYZ's `dt=`).
    pub dt: f64,
    /// Box edges `[L_x, L_y, L_z]` in units of r_c.
    pub box_lengths: [f64; 3],
    /// Positions in `[0, L)`, units of r_c.
    pub positions: Vec<[f64; 3]>,
    /// Velocities in r_c per time unit; `None` leaves them out of the file.
    pub velocities: Option<Vec<[f64; 3]>>,
    /// Periodic image of each particle (how many box edges it has crossed); `None` leaves them
    /// out.
    pub images: Option<Vec<[i32; 3]>>,
    /// Index into `types` of each particle.
    pub typeid: Vec<u32>,
    /// Type names.
    pub types: Vec<String>,
    /// Masses; `None` leaves them out (readers then take 1).
    pub masses: Option<Vec<f64>>,
    /// Scalar observables of this frame, by name (GSD `log/<name>`, extended XYZ comment keys).
    pub log: Vec<(String, f64)>,
    /// Bonds between the particles (GSD `bonds/...`, which OVITO draws; not in the text
    /// formats); `None` leaves them out.
    pub bonds: Option<Bonds>,
}

/// The bonds of a frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Bonds {
    /// Bond type names.
    pub types: Vec<String>,
    /// Index into `types` of each bond.
    pub typeid: Vec<u32>,
    /// The indices of the two particles of each bond.
    pub group: Vec<[u32; 2]>,
}

impl Frame {
    /// Number of particles.
    pub fn len(&self) -> usize {
        self.positions.len()
    }

    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }

    /// The type name of particle `i`.
    fn type_name(&self, i: usize) -> &str {
        self.types
            .get(self.typeid[i] as usize)
            .map_or("A", String::as_str)
    }

    /// Check that every per-particle array has one entry per particle and every type id names
    /// a type.
    fn check(&self) -> Result<(), TrajectoryError> {
        let n = self.len();
        let lengths = [
            ("velocities", self.velocities.as_ref().map(Vec::len)),
            ("images", self.images.as_ref().map(Vec::len)),
            ("typeid", Some(self.typeid.len())),
            ("masses", self.masses.as_ref().map(Vec::len)),
        ];
        for (what, len) in lengths {
            if let Some(len) = len.filter(|&len| len != n) {
                return Err(TrajectoryError::Frame(format!(
                    "{what} has {len} entries for {n} particles"
                )));
            }
        }
        if let Some((name, _)) = self.log.iter().find(|(n, _)| n == "time" || n == "dt") {
            return Err(TrajectoryError::Frame(format!(
                "log name {name:?} is reserved: every frame carries its time and dt"
            )));
        }
        if let Some(t) = self
            .typeid
            .iter()
            .find(|&&t| t as usize >= self.types.len())
        {
            return Err(TrajectoryError::Frame(format!(
                "typeid {t} names no type (types: {:?})",
                self.types
            )));
        }
        if let Some(b) = &self.bonds {
            b.check(n)?;
        }
        Ok(())
    }
}

impl Bonds {
    /// Check that every bond has a type that names one and joins two particles of the `n`.
    fn check(&self, n: usize) -> Result<(), TrajectoryError> {
        let bad = |message: String| Err(TrajectoryError::Frame(message));
        if self.typeid.len() != self.group.len() {
            let (t, g) = (self.typeid.len(), self.group.len());
            return bad(format!("bonds: {t} type ids for {g} bonds"));
        }
        for (k, (&t, &[i, j])) in self.typeid.iter().zip(&self.group).enumerate() {
            if t as usize >= self.types.len() {
                return bad(format!("bond {k}: typeid {t} names no bond type"));
            }
            if i == j || i as usize >= n || j as usize >= n {
                return bad(format!(
                    "bond {k} joins particles {i} and {j}: two different particles of the {n}"
                ));
            }
        }
        Ok(())
    }
}

/// What went wrong reading or writing a trajectory.
#[derive(Debug, Error)]
pub enum TrajectoryError {
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error(
        "trajectory file {0:?}: unknown extension; valid: .gsd (HOOMD schema), .xyz (extended \
         XYZ), .lammpstrj or .dump (LAMMPS dump text)"
    )]
    Extension(PathBuf),
    #[error("{path}: {message}")]
    Format { path: PathBuf, message: String },
    #[error("frame: {0}")]
    Frame(String),
}

impl TrajectoryError {
    fn io(path: &Path) -> impl FnOnce(std::io::Error) -> TrajectoryError + '_ {
        move |source| TrajectoryError::Io {
            path: path.to_path_buf(),
            source,
        }
    }
}

/// The trajectory formats, chosen by extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// `.gsd`: GSD file layer 2.1, HOOMD schema 1.4.
    Gsd,
    /// `.xyz`: extended XYZ, one block per frame.
    ExtendedXyz,
    /// `.lammpstrj` or `.dump`: LAMMPS dump text (`ITEM:` blocks, atom ids and types from 1).
    LammpsDump,
}

impl Format {
    /// The format of `path`'s extension.
    pub fn of(path: &Path) -> Result<Format, TrajectoryError> {
        match path.extension().and_then(|e| e.to_str()) {
            Some("gsd") => Ok(Format::Gsd),
            Some("xyz") => Ok(Format::ExtendedXyz),
            Some("lammpstrj" | "dump") => Ok(Format::LammpsDump),
            _ => Err(TrajectoryError::Extension(path.to_path_buf())),
        }
    }
}

/// An open trajectory file that frames are appended to.
pub enum Writer {
    Gsd(Box<gsd::GsdWriter>),
    Text(text::TextWriter),
}

impl Writer {
    /// Create (or truncate) `path` in the format of its extension. `log_names` are the
    /// observables every frame will carry (GSD reserves their names up front).
    pub fn create(path: &Path, log_names: &[&str]) -> Result<Writer, TrajectoryError> {
        Ok(match Format::of(path)? {
            Format::Gsd => Writer::Gsd(Box::new(gsd::GsdWriter::create(path, log_names)?)),
            f => Writer::Text(text::TextWriter::create(path, f)?),
        })
    }

    /// Append `frame` as the next frame.
    pub fn append(&mut self, frame: &Frame) -> Result<(), TrajectoryError> {
        frame.check()?;
        match self {
            Writer::Gsd(w) => w.append(frame),
            Writer::Text(w) => w.append(frame),
        }
    }
}
