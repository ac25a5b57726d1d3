//! Trajectories of `dpd run` (the scene's `[trajectory]` table or `--trajectory FILE --every
//! T`) and runs started from a frame of a GSD file (`init = "FILE.gsd[:frame]"`, `--init`).
//! The files themselves are written and read by the `dpd-trajectory` crate.

use crate::images::Images;
use dpd_core::observe::thermo;
use dpd_core::{ParamError, System, Vec3};
use dpd_trajectory::gsd::GsdReader;
use dpd_trajectory::{Format, Frame, Writer};
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// What a trajectory holds besides positions, box, step and types.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Field {
    /// Velocities (momentum / mass), r_c per time unit.
    Velocity,
    /// Masses.
    Mass,
    /// Periodic images (crossings of each pair of box faces since the run's start; followed
    /// after every step, see [`Images`]). Not under Lees-Edwards boundaries.
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

/// The observables a frame logs, in the order of [`frame`]'s values.
const LOG_NAMES: [&str; 4] = [
    "kinetic_temperature",
    "configurational_temperature",
    "potential_energy",
    "pressure",
];

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

    /// The file of the run with `seed`: `file` itself when the scene has one run.
    pub fn path(&self, seed: u64, runs: u64) -> PathBuf {
        if runs <= 1 {
            return self.file.clone();
        }
        let stem = self.file.file_stem().unwrap_or_default().to_string_lossy();
        let ext = self.file.extension().unwrap_or_default().to_string_lossy();
        self.file.with_file_name(format!("{stem}-seed{seed}.{ext}"))
    }
}

/// Writes one run's frames: the state at step 0 and every `every_steps` after.
pub struct Recorder {
    writer: Writer,
    fields: Vec<Field>,
    every_steps: u64,
    path: PathBuf,
    /// With the `image` field: the images, which need the positions after every step.
    images: Option<Images>,
}

impl Recorder {
    /// Create the file of run `seed` and write the initial state as frame 0. Images count from
    /// this state (also when it comes from `init`).
    pub fn start(
        spec: &TrajectorySpec,
        dt: f64,
        seed: u64,
        runs: u64,
        sys: &mut System,
    ) -> Result<Recorder, ParamError> {
        let fields = match &spec.fields {
            Some(fields) => fields.clone(),
            None => {
                let mut all = vec![Field::Velocity, Field::Mass, Field::Observables];
                if sys.shear().is_none() {
                    all.push(Field::Image);
                }
                all
            }
        };
        let images = match fields.contains(&Field::Image) {
            true => Some(Images::start(sys)?),
            false => None,
        };
        let path = spec.path(seed, runs);
        let names: &[&str] = match fields.contains(&Field::Observables) {
            true => &LOG_NAMES,
            false => &[],
        };
        let writer = Writer::create(&path, names)
            .map_err(|e| ParamError::new("trajectory.file", path.display(), e.to_string()))?;
        let mut r = Recorder {
            writer,
            fields,
            every_steps: spec.every_steps(dt),
            path,
            images,
        };
        r.record(sys)?;
        Ok(r)
    }

    /// The next step after `step` at which the recorder needs the state: the next frame, or
    /// the next step when it follows images.
    pub fn next_stop(&self, step: u64) -> u64 {
        match self.images {
            Some(_) => step + 1,
            None => (step / self.every_steps + 1) * self.every_steps,
        }
    }

    /// Follow the images over the steps since the last stop (one step: see [`Self::next_stop`])
    /// and append a frame if one is due at the system's step.
    pub fn record_if_due(&mut self, sys: &mut System) -> Result<(), ParamError> {
        if let Some(images) = &mut self.images {
            images.update(sys);
        }
        if sys.step().is_multiple_of(self.every_steps) {
            self.record(sys)?;
        }
        Ok(())
    }

    fn record(&mut self, sys: &mut System) -> Result<(), ParamError> {
        let mut f = frame(sys, &self.fields);
        f.images = self.images.as_ref().map(|i| i.by_id().to_vec());
        self.writer
            .append(&f)
            .map_err(|e| ParamError::new("trajectory.file", self.path.display(), e.to_string()))
    }
}

/// The system's state as a frame, particles in the order of their ids (the order in which
/// the system was built; the storage order changes as the system sorts itself).
pub fn frame(sys: &mut System, fields: &[Field]) -> Frame {
    let ids: Vec<usize> = sys.ids().iter().map(|&i| i as usize).collect();
    let in_id_order = |values: &[Vec3], scale: &dyn Fn(usize) -> f64| {
        let mut out = vec![[0.0; 3]; values.len()];
        for (k, &i) in ids.iter().enumerate() {
            let s = scale(k);
            out[i] = [values[k].x * s, values[k].y * s, values[k].z * s];
        }
        out
    };
    let masses = sys.masses().to_vec();
    let positions = in_id_order(sys.positions(), &|_| 1.0);
    let velocities = fields
        .contains(&Field::Velocity)
        .then(|| in_id_order(sys.momenta(), &|k| 1.0 / masses[k]));
    let mut typeid = vec![0; ids.len()];
    let mut mass = vec![0.0; ids.len()];
    for (k, &i) in ids.iter().enumerate() {
        typeid[i] = u32::from(sys.kinds()[k]);
        mass[i] = masses[k];
    }
    let log = match fields.contains(&Field::Observables) {
        true => {
            let t = thermo(sys);
            let values = [
                t.kinetic_temperature,
                t.config_numerator / t.config_denominator,
                t.potential_energy,
                t.pressure,
            ];
            LOG_NAMES
                .iter()
                .map(|n| n.to_string())
                .zip(values)
                .collect()
        }
        false => Vec::new(),
    };
    let types = (0..sys.params().types())
        .map(|t| type_name(t as u32))
        .collect();
    Frame {
        step: sys.step(),
        box_lengths: sys.boundary().lengths().into(),
        positions,
        velocities,
        images: None,
        typeid,
        types,
        masses: fields.contains(&Field::Mass).then_some(mass),
        log,
    }
}

/// Type `t`'s name: A, B, ... Z, then T26, T27, ...
fn type_name(t: u32) -> String {
    match char::from_u32(u32::from(b'A') + t) {
        Some(c) if t < 26 => c.to_string(),
        _ => format!("T{t}"),
    }
}

/// `init = "FILE.gsd[:frame]"`: the file and the frame (default: the last).
#[derive(Clone, Debug, PartialEq)]
pub struct InitSpec {
    pub file: PathBuf,
    pub frame: Option<u64>,
}

impl InitSpec {
    /// Parse `FILE.gsd` or `FILE.gsd:K`.
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
        if !file.ends_with(".gsd") {
            return Err(ParamError::new(
                "init",
                text,
                "must be a GSD file, FILE.gsd or FILE.gsd:frame",
            ));
        }
        Ok(InitSpec {
            file: PathBuf::from(file),
            frame,
        })
    }

    /// The frame, checked against the scene's particle count and box.
    pub fn read(&self, n: usize, box_lengths: [f64; 3]) -> Result<Frame, ParamError> {
        let bad = |message: String| ParamError::new("init", self.file.display(), message);
        let reader = GsdReader::open(&self.file).map_err(|e| bad(e.to_string()))?;
        let k = match self.frame {
            Some(k) => k,
            None if reader.frames() > 0 => reader.frames() - 1,
            None => return Err(bad("the file has no frame".into())),
        };
        let f = reader.frame(k).map_err(|e| bad(e.to_string()))?;
        if f.len() != n {
            return Err(bad(format!(
                "frame {k} has {} particles, the scene {n}: set n (or box and density) to match",
                f.len()
            )));
        }
        let mismatch = |a: f64, b: f64| (a - b).abs() > 1e-5 * b.abs();
        if (0..3).any(|d| mismatch(f.box_lengths[d], box_lengths[d])) {
            return Err(bad(format!(
                "frame {k} has box {:?}, the scene {box_lengths:?}: set box (or n and density) \
                 to match",
                f.box_lengths
            )));
        }
        Ok(f)
    }
}

/// Positions, momenta, masses (`mass` where the file has none) and types of `f` for a system
/// of `types` particle types.
pub type InitialState = (Vec<Vec3>, Vec<Vec3>, Vec<f64>, Vec<u16>);

pub fn initial_state(f: &Frame, mass: f64, types: usize) -> Result<InitialState, ParamError> {
    if let Some(i) = f.typeid.iter().position(|&t| t as usize >= types) {
        return Err(ParamError::new(
            format!("init: typeid of particle {i}"),
            f.typeid[i],
            format!(
                "the scene has {types} particle type(s): type ids 0 to {}",
                types - 1
            ),
        ));
    }
    let to = |v: &[f64; 3]| Vec3::new(v[0], v[1], v[2]);
    let masses = f.masses.clone().unwrap_or_else(|| vec![mass; f.len()]);
    let q = f.positions.iter().map(to).collect();
    let p = match &f.velocities {
        Some(v) => v.iter().zip(&masses).map(|(v, m)| to(v) * *m).collect(),
        None => vec![Vec3::zeros(); f.len()],
    };
    let kinds = f.typeid.iter().map(|&t| t as u16).collect();
    Ok((q, p, masses, kinds))
}
