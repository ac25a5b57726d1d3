//! Runs started from a frame of a GSD file (`init = "FILE.gsd[:frame]"`) or from a LAMMPS data
//! file (`init = "FILE.data"`), read by the `dpd-trajectory` crate (`--init`),
//! and where their trajectories' counters start.

use crate::data_bonds::topology_of;
use crate::data_file::{frame_of, pair_coefficients};
use crate::pair_coefficients::PairCoefficients;
use dpd_core::{ParamError, Topology, Vec3};
use dpd_trajectory::gsd::GsdReader;
use dpd_trajectory::lammps_data::DataFile;
use dpd_trajectory::{Frame, TrajectoryError};
use std::path::PathBuf;

/// `init = "FILE.gsd[:frame]"` (the frame, default the last) or `init = "FILE.data"`.
#[derive(Clone, Debug, PartialEq)]
pub struct InitSpec {
    pub file: PathBuf,
    pub format: InitFormat,
}

/// What kind of file an `init` names, told by [`InitSpec::parse`] from its name.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum InitFormat {
    /// A GSD file and its frame (`None`: the last).
    Gsd { frame: Option<u64> },
    /// A LAMMPS data file.
    Data,
}

/// What a run starts from: a frame, and a data file's pair coefficients and its bonds and
/// angles.
pub struct Start {
    pub frame: Frame,
    pub coefficients: Option<PairCoefficients>,
    pub topology: Option<Topology>,
    /// The file's id and atom ids of each bond, in the topology's order (a data file's; empty
    /// for a GSD frame), to name a bond as the file does ([`name_bond`]).
    pub bond_ids: Vec<(u64, [u64; 2])>,
}

/// `e`, from building a system that started from a data file whose bonds are `bond_ids`, with
/// the file's bond named where `e` names one by its index (`bonds[k]`: a FENE bond at or
/// beyond R0 at the start).
pub fn name_bond(e: ParamError, bond_ids: &[(u64, [u64; 2])]) -> ParamError {
    let index = e
        .field
        .strip_prefix("bonds[")
        .and_then(|k| k.strip_suffix(']'));
    match index.and_then(|k| bond_ids.get(k.parse::<usize>().ok()?)) {
        Some((id, [a, b])) => ParamError {
            field: format!("init: Bonds: bond {id}"),
            value: format!("atoms {a} and {b} of the file ({})", e.value),
            allowed: e.allowed,
        },
        None => e,
    }
}

impl InitSpec {
    /// Parse `FILE.gsd`, `FILE.gsd:K` or `FILE.data`.
    pub fn parse(text: &str) -> Result<InitSpec, ParamError> {
        let (file, frame) = match text.rsplit_once(':') {
            Some((file, k)) if file.ends_with(".gsd") => {
                let k = k.parse().map_err(|_| {
                    ParamError::new(
                        "init",
                        text,
                        "the frame after ':' must be a whole number >= 0",
                    )
                })?;
                (file, Some(k))
            }
            _ => (text, None),
        };
        let format = if file.ends_with(".gsd") {
            InitFormat::Gsd { frame }
        } else if file.ends_with(".data") {
            InitFormat::Data
        } else {
            return Err(ParamError::new(
                "init",
                text,
                "must be a GSD file, FILE.gsd or FILE.gsd:frame, or a LAMMPS data file, \
                 FILE.data",
            ));
        };
        Ok(InitSpec {
            file: PathBuf::from(file),
            format,
        })
    }

    /// The particle count and box edges of the start, for a scene that leaves them to the
    /// file (docs/scenes.md, `init`).
    pub fn size(&self) -> Result<(usize, [f64; 3]), ParamError> {
        let bad = |message: String| ParamError::new("init", self.file.display(), message);
        match self.format {
            InitFormat::Data => {
                // The header alone: the file is read in full when the run starts, and a
                // second full parse here left ~120 bytes per particle of freed allocations in
                // the resident set (24 000 beads).
                let (atoms, bounds) =
                    DataFile::read_size(&self.file).map_err(|e| bad(without_path(e)))?;
                Ok((atoms, bounds.map(|[lo, hi]| hi - lo)))
            }
            InitFormat::Gsd { frame } => {
                let (frame, _) = self.gsd_frame(frame)?;
                Ok((frame.len(), frame.box_lengths))
            }
        }
    }

    /// The start, checked against the scene's particle count, box and type names (`names`,
    /// empty without species).
    pub fn read(
        &self,
        n: usize,
        box_lengths: [f64; 3],
        names: &[String],
    ) -> Result<Start, ParamError> {
        let bad = |message: String| ParamError::new("init", self.file.display(), message);
        let (k, start) = match self.format {
            InitFormat::Data => {
                let data = DataFile::read(&self.file).map_err(|e| bad(without_path(e)))?;
                let frame = frame_of(&data).map_err(bad)?;
                let coefficients = pair_coefficients(&data)?;
                let types = data.atom_types as usize;
                if !names.is_empty() && types != names.len() {
                    return Err(bad(format!(
                        "has {types} atom types, the scene {} species",
                        names.len()
                    )));
                }
                if let Some(labels) = data.type_labels.as_ref().filter(|_| !names.is_empty()) {
                    if labels != names {
                        return Err(bad(format!(
                            "its Atom Type Labels {labels:?} are not the scene's species \
                             {names:?} in their order"
                        )));
                    }
                }
                let topology = topology_of(&data)?;
                let start = Start {
                    frame,
                    coefficients,
                    topology,
                    bond_ids: data.bonds.iter().map(|b| (b.id, b.atoms)).collect(),
                };
                ("the file".to_string(), start)
            }
            InitFormat::Gsd { frame } => {
                let (frame, k) = self.gsd_frame(frame)?;
                if !names.is_empty() && frame.types != names {
                    return Err(ParamError::new(
                        "init: types",
                        format!("{:?}", frame.types),
                        format!("must be the scene's species, {names:?}, in their order"),
                    ));
                }
                let start = Start {
                    frame,
                    coefficients: None,
                    topology: None,
                    bond_ids: Vec::new(),
                };
                (format!("frame {k}"), start)
            }
        };
        let f = &start.frame;
        if f.len() != n {
            return Err(bad(format!(
                "{k} has {} particles, the scene {n}: leave n, box and density out to take \
                 the file's, or set them to match",
                f.len()
            )));
        }
        let mismatch = |a: f64, b: f64| (a - b).abs() > 1e-5 * b.abs();
        if (0..3).any(|d| mismatch(f.box_lengths[d], box_lengths[d])) {
            return Err(bad(format!(
                "{k} has box {:?}, the scene {box_lengths:?}: leave n, box and density out \
                 to take the file's, or set them to match",
                f.box_lengths
            )));
        }
        Ok(start)
    }

    /// The GSD file's frame `frame` (`None`: the last) and its index.
    fn gsd_frame(&self, frame: Option<u64>) -> Result<(Frame, u64), ParamError> {
        let bad = |message: String| ParamError::new("init", self.file.display(), message);
        let reader = GsdReader::open(&self.file).map_err(|e| bad(without_path(e)))?;
        let k = match frame {
            Some(k) => k,
            None if reader.frames() > 0 => reader.frames() - 1,
            None => return Err(bad("the file has no frame".into())),
        };
        let f = reader.frame(k).map_err(|e| bad(without_path(e)))?;
        Ok((f, k))
    }
}

/// `e`'s message without the file's path, which the error naming `init` shows already.
fn without_path(e: TrajectoryError) -> String {
    match e {
        TrajectoryError::Io { source, .. } => source.to_string(),
        TrajectoryError::Format { message, .. } => message,
        other => other.to_string(),
    }
}

/// Where a run's counters start, as HOOMD continues them from a GSD frame: the step, the
/// simulation time and the periodic images (by particle id) of its first frame. The system
/// itself counts its steps from 0 (its noise, sampling and run length do not depend on where
/// the trajectory started); the files show `origin.step + step`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Origin {
    pub step: u64,
    pub time: f64,
    pub images: Option<Vec<[i32; 3]>>,
}

impl Origin {
    /// The origin of a run started from `init` (a frame of a GSD file) at time step `dt`: the
    /// frame's step, time and images. A file without `log/time` and `log/dt` (written by
    /// another program) gives the time step x `dt`; one without images, images 0.
    pub fn of_frame(f: &Frame, dt: f64) -> Origin {
        Origin {
            step: f.step,
            time: if f.dt > 0.0 {
                f.time
            } else {
                f.step as f64 * dt
            },
            images: f.images.clone(),
        }
    }
}

/// Positions, momenta, masses and types of a frame.
pub type InitialState = (Vec<Vec3>, Vec<Vec3>, Vec<f64>, Vec<u16>);

/// The state of `f` for a scene whose types have masses `type_masses` (a particle's mass where
/// the file has none).
pub fn initial_state(f: &Frame, type_masses: &[f64]) -> Result<InitialState, ParamError> {
    let types = type_masses.len();
    if let Some(i) = f.typeid.iter().position(|&t| t as usize >= types) {
        let names = f.types.join(", ");
        return Err(ParamError::new(
            format!("init: typeid of particle {i}"),
            f.typeid[i],
            format!(
                "the frame has {} types ({names}), the scene {types}: give [[species]] {names} \
                 in this order with their [pairs], or a data file's PairIJ Coeffs (type ids 0 \
                 to {})",
                f.types.len(),
                types - 1
            ),
        ));
    }
    let to = |v: &[f64; 3]| Vec3::new(v[0], v[1], v[2]);
    let masses = match &f.masses {
        Some(m) => m.clone(),
        None => f.typeid.iter().map(|&t| type_masses[t as usize]).collect(),
    };
    let q = f.positions.iter().map(to).collect();
    let p = match &f.velocities {
        Some(v) => v.iter().zip(&masses).map(|(v, m)| to(v) * *m).collect(),
        None => vec![Vec3::zeros(); f.len()],
    };
    let kinds = f.typeid.iter().map(|&t| t as u16).collect();
    Ok((q, p, masses, kinds))
}
