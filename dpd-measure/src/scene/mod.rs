//! Scenes: what to simulate and how long, read from TOML or from keys given by a caller (the
//! command line's flags, Python's keywords), validated with messages that name the key.
//!
//! A scene names only what it needs; every key has the default of the standard equilibrium box
//! of algorithms.md section 8 (N = 500, density 3, a = 25, gamma = 4.5, k_B T = 1, m = 1,
//! s = 2, 1000 time units averaged over the last 80 %). Its keys stay flat in the file, as
//! users write them, and belong to sections that read and check themselves:
//!
//! | section | file | keys |
//! |---|---|---|
//! | [`RunSpec`] | `run.rs` | `scheme`, `dt`, `time`, `average_fraction`, `sample_interval`, `seed`, `runs`, `threads` |
//! | [`Physics`] | `physics.rs` | `a`, `gamma`, `kbt`, `mass`, `weight_exponent`, `collision_rate`, `thermostat_mass`, `thermostat_friction`, `shear_rate`, `body_force` |
//! | [`Species`] | `species.rs` | `[[species]]`, `[pairs]` |
//! | [`Molecules`] | `molecules.rs` | `[[bond_types]]`, `[[angle_types]]`, `[[molecules]]`, `exclude_bonded` |
//! | [`Geometry`] | `geometry.rs` | `n`, `density`, `box`, `skin`, `init`, `init_reset`, `[walls]` |
//! | [`Observe`] | `observe.rs` | `[rdf]`, `[vacf]`, `[profile]`, `energy_balance`, `like_neighbours`, `processing` |
//! | [`Output`] | `output.rs` | `description`, `[trajectory]`, `write_data` |
//! | [`SweepSpec`] | `sweep.rs` | `[sweep]` |
//!
//! Each section takes its keys out of the parsed table ([`section::take`]); a key no section
//! takes is refused with the nearest known one. To add a section (species, bonds, molecules):
//! write its file with a `Serialize + Deserialize + Default` struct (`deny_unknown_fields`,
//! `default`) and a `validate` that names its keys, add it to [`Scene`] as a `flatten`ed field,
//! take it in [`Scene::from_keys`] and check it in [`Scene::validate`]. How the system is built
//! from the sections is in `build.rs`.

mod build;
mod check;
pub mod geometry;
pub mod molecules;
pub mod observe;
pub mod output;
pub mod physics;
pub mod run;
pub mod section;
pub mod species;
pub mod sweep;

pub use check::{MAX_PARTICLES, MAX_STEPS, MAX_THREADS_PER_CORE};
pub use geometry::{Geometry, WallSpec};
pub use molecules::{AngleType, BondType, ChainSpec, Molecules};
pub use observe::{Observe, ProfileSpec, RdfSpec, VacfSpec};
pub use output::{Field, Output, TrajectorySpec};
pub use physics::Physics;
pub use run::RunSpec;
pub use section::Keys;
pub use species::{PairSpec, Species, TypeSpec};
pub use sweep::{Observable, SweepSpec};

use crate::start::{InitFormat, InitSpec};
use dpd_core::ParamError;
use dpd_trajectory::lammps_data::DataFile;
use section::{names, take, take_table, unknown};
use serde::Serialize;
use std::path::Path;
use thiserror::Error;

/// One simulation set-up, by section. It serialises flat, with the keys of a scene file.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Scene {
    #[serde(flatten)]
    pub output: Output,
    #[serde(flatten)]
    pub run: RunSpec,
    #[serde(flatten)]
    pub physics: Physics,
    #[serde(flatten)]
    pub species: Species,
    #[serde(flatten)]
    pub molecules: Molecules,
    #[serde(flatten)]
    pub geometry: Geometry,
    #[serde(flatten)]
    pub observe: Observe,
    pub sweep: Option<SweepSpec>,
}

/// A scene that cannot be read or is not valid.
#[derive(Debug, Error)]
pub enum SceneError {
    #[error("scene {path}: {source}")]
    Io {
        path: String,
        #[source]
        source: std::io::Error,
    },
    #[error("scene {path}: {message}")]
    Toml { path: String, message: String },
    #[error("scene: {0}")]
    Invalid(#[from] ParamError),
}

impl Scene {
    /// Read a scene from its keys; `path` names their source in messages. Not validated, but
    /// with `init` the file is read for the particle count and box the keys leave out
    /// ([`Geometry::size_from_init`]).
    pub fn from_keys(mut keys: Keys, path: &str) -> Result<Scene, SceneError> {
        let error = |message: String| SceneError::Toml {
            path: path.into(),
            message,
        };
        let given = geometry::Given {
            n: keys.contains_key("n"),
            box_lengths: keys.contains_key("box"),
            density: keys.contains_key("density"),
        };
        let mut scene = Scene {
            output: take(&mut keys).map_err(error)?,
            run: take(&mut keys).map_err(error)?,
            physics: take(&mut keys).map_err(error)?,
            species: take(&mut keys).map_err(error)?,
            molecules: take(&mut keys).map_err(error)?,
            geometry: take(&mut keys).map_err(error)?,
            observe: take(&mut keys).map_err(error)?,
            sweep: take_table(&mut keys, "sweep").map_err(error)?,
        };
        let known: Vec<&str> = [
            names::<Output>(),
            names::<RunSpec>(),
            names::<Physics>(),
            names::<Species>(),
            names::<Molecules>(),
            names::<Geometry>(),
            names::<Observe>(),
            &["sweep"],
        ]
        .concat();
        if let Some(message) = unknown(&keys, &known) {
            return Err(error(message));
        }
        scene.geometry.size_from_init(given)?;
        // The header and the results file show the reference the sweep uses.
        if let Some(w) = &mut scene.sweep {
            w.reference = Some(w.reference().to_string());
        }
        Ok(scene)
    }

    /// Parse TOML text; `path` names the source in messages. Not validated.
    pub fn from_toml(text: &str, path: &str) -> Result<Scene, SceneError> {
        Scene::from_keys(parse(text, path)?, path)
    }

    /// Read a scene file. Not validated.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        Scene::from_keys(read(path)?, &path.display().to_string())
    }

    /// The scene file `file` (or the default scene) with `keys` merged over its own (tables
    /// key by key), validated. `keys` are scene keys as a scene file writes them: the command
    /// line's flags and Python's keywords arrive here. A caller's `n` over a file's `box`,
    /// which would ignore it, is refused.
    pub fn resolve(file: Option<&Path>, keys: &Keys) -> Result<Scene, SceneError> {
        let (mut base, path) = match file {
            Some(path) => (read(path)?, path.display().to_string()),
            None => (Keys::new(), "(default)".to_string()),
        };
        let file_box = base.contains_key("box") && !keys.contains_key("box");
        section::merge(&mut base, keys);
        let scene = Scene::from_keys(base, &path)?;
        if let (true, Some(n), Some(edges)) = (file_box, keys.get("n"), scene.geometry.box_lengths)
        {
            let why = format!(
                "is not used with the scene file's box = {edges:?}, which holds {} particles at \
                 density {}: change the density, or give a box",
                scene.geometry.particles(),
                scene.geometry.density
            );
            return Err(ParamError::new("n", n, why).into());
        }
        scene.validate()?;
        Ok(scene)
    }

    /// Check every key; the first invalid one is reported by name.
    pub fn validate(&self) -> Result<(), ParamError> {
        self.run.validate()?;
        self.physics.validate()?;
        self.geometry.validate()?;
        let default_a = Physics::default().a;
        let particles = self.geometry.particles();
        self.species
            .validate(particles, self.physics.a, default_a)?;
        check::require(
            "like_neighbours",
            true,
            !self.observe.like_neighbours || self.species.species.is_some(),
            "needs [[species]] (with one species every neighbour is like)",
        )?;
        let chains = !self.chain_plans()?.is_empty();
        // A data file's bonds are known once it is read (`Scene::system`).
        let init = self.geometry.init.is_some();
        self.molecules.check_exclusion(chains || init)?;
        self.observe.validate(self.geometry.shortest_edge()?)?;
        if self.observe.processing != 0.0 {
            let other = if self.geometry.walls.is_some() {
                Some("walls")
            } else if self.physics.sheared() {
                Some("a shear rate")
            } else if self.physics.body_force.is_some() {
                Some("a body force")
            } else if chains {
                Some("bonds")
            } else {
                None
            };
            if let Some(other) = other {
                return Err(ParamError::new(
                    "processing",
                    self.observe.processing,
                    format!(
                        "the scene has {other}: processing is for the periodic bulk at \
                         equilibrium with pair forces only (0 turns it off)"
                    ),
                ));
            }
        }
        self.output.validate()?;
        if let Some(w) = &self.sweep {
            let walls = self.geometry.walls.is_some();
            w.validate(self.run.time, self.physics.sheared(), walls)?;
        }
        Ok(())
    }

    /// The `[sweep]` table, or the default one.
    pub fn sweep_spec(&self) -> SweepSpec {
        self.sweep.clone().unwrap_or_default()
    }

    /// Samples between g(r) records at `dt` (at least 1); see [`RdfSpec::interval`].
    pub fn rdf_stride(&self, dt: f64) -> u64 {
        let sample = self.run.sample_every(dt) as f64 * dt;
        match self.observe.rdf.as_ref().and_then(|r| r.interval) {
            Some(interval) => ((interval / sample).round() as u64).max(1),
            None => 1,
        }
    }

    /// The effective parameters as TOML, for headers; with `box`, the ignored `n` is left out
    /// and the particle count given in a comment.
    pub fn to_toml(&self) -> String {
        let mut table = match toml::Table::try_from(self) {
            Ok(table) => table,
            Err(e) => return format!("(scene not printable: {e})"),
        };
        let mut out = String::new();
        if self.geometry.box_lengths.is_some() {
            table.remove("n");
            out = format!(
                "# {} particles (density x box volume)\n",
                self.geometry.particles()
            );
        }
        out + &table.to_string() + &self.init_comments()
    }

    /// The coefficient sections of an `init` LAMMPS data file, each heading (as "Pair Coeffs
    /// # dpd") with its lines as the file writes them: they set what the scene's keys do not
    /// show (without species, the file's pair coefficients are used instead of `a` and
    /// `gamma`). Empty for another start, or a file that cannot be read (the run then says
    /// why).
    pub fn init_coefficients(&self) -> Vec<(String, Vec<String>)> {
        let data_file = self
            .geometry
            .init
            .as_deref()
            .and_then(|init| InitSpec::parse(init).ok())
            .filter(|spec| spec.format == InitFormat::Data);
        data_file
            .and_then(|spec| DataFile::coefficient_lines(&spec.file).ok())
            .unwrap_or_default()
    }

    /// [`Self::init_coefficients`] as comment lines, one per section.
    fn init_comments(&self) -> String {
        let instead = match self.species.species {
            None => " (used instead of a and gamma)",
            Some(_) => "",
        };
        let init = self.geometry.init.as_deref().unwrap_or_default();
        let line = |(heading, body): &(String, Vec<String>)| {
            let used = if heading.starts_with("Pair") {
                instead
            } else {
                ""
            };
            format!("# {init}, {heading}{used}: {}\n", body.join("; "))
        };
        self.init_coefficients().iter().map(line).collect()
    }
}

fn parse(text: &str, path: &str) -> Result<Keys, SceneError> {
    toml::from_str(text).map_err(|e| SceneError::Toml {
        path: path.into(),
        message: e.to_string(),
    })
}

fn read(path: &Path) -> Result<Keys, SceneError> {
    let text = std::fs::read_to_string(path).map_err(|source| SceneError::Io {
        path: path.display().to_string(),
        source,
    })?;
    parse(&text, &path.display().to_string())
}

#[cfg(test)]
mod tests;
