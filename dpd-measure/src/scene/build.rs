//! The system of a scene: its sections put together into a `dpd_core::System`, and where the
//! trajectories of its runs count from.

use super::molecules::{ChainPlan, Context};
use super::{check, Scene};
use crate::chains;
use crate::data_file::same_coefficients;
use crate::observer::TypeNames;
use crate::start::{initial_state, name_bond, InitSpec, Origin};
use dpd_core::bonded::{Topology, TopologyBuilder};
use dpd_core::init::{freeze_outside, maxwell_momenta, uniform_positions};
use dpd_core::{ParamError, Params, System, Vec3};
use dpd_trajectory::Frame;

impl Scene {
    /// The initial state of run `seed` at time step `dt`: uniform positions, types by id in
    /// the order of `[[species]]`, Maxwell momenta with the total momentum removed (with
    /// `init`, the frame's positions, velocities, masses and types instead, and a data file's
    /// pair coefficients); with `[walls]`,
    /// the particles outside the channel are frozen (and their momenta zeroed).
    pub fn system(&self, dt: f64, seed: u64) -> Result<System, ParamError> {
        let (geometry, physics) = (&self.geometry, &self.physics);
        let bx = geometry.periodic_box()?;
        let n = geometry.particles();
        let type_masses = self.type_masses();
        let names = self.species.names();
        let (state, params, topology, bond_ids) = match &geometry.init {
            Some(init) => {
                let lengths = bx.lengths().into();
                let start = InitSpec::parse(init)?.read(n, lengths, &names)?;
                let params = match (start.coefficients, &self.species.species) {
                    (Some(c), None) => c.apply(physics.builder()).build()?,
                    (Some(c), Some(_)) => {
                        let scene = self.species.coefficients(physics.gamma)?;
                        same_coefficients(&c, &scene, &names)?;
                        self.params()?
                    }
                    (None, _) => self.params()?,
                };
                // A data file's pair coefficients may bring types a scene without species
                // lacks: their particles take the scene's mass where the file has none.
                let mut masses = type_masses;
                masses.resize(params.types(), physics.mass);
                let state = initial_state(&start.frame, &masses)?;
                let topology = self.init_topology(start.topology, &start.frame)?;
                (state, params, topology, start.bond_ids)
            }
            None => {
                let plans = self.chain_plans()?;
                let kinds = match (self.species.species.is_some(), plans.is_empty()) {
                    (_, false) => chains::kinds(&plans, &self.type_counts()?),
                    (true, true) => self.species.kinds(n)?,
                    (false, true) => vec![0; n],
                };
                let masses: Vec<f64> = kinds.iter().map(|&t| type_masses[t as usize]).collect();
                let mut q = chains::random_walks(&plans, &bx, seed);
                q.extend(uniform_positions(&bx, n - q.len(), seed));
                let p = maxwell_momenta(&masses, physics.kbt, seed);
                let state = (q, p, masses, kinds);
                (state, self.params()?, self.topology()?, Vec::new())
            }
        };
        let (q, mut p, masses, kinds) = state;
        let mut builder = System::builder(params, bx, q.clone())
            .masses(masses)
            .kinds(kinds)
            .dt(dt)
            .seed(seed)
            .skin(geometry.skin);
        if let Some(w) = &geometry.walls {
            let walls = w.walls()?;
            let frozen = freeze_outside(&walls, &q, &mut p);
            builder = builder.walls(walls).frozen(frozen);
        }
        self.molecules.check_exclusion(topology.is_some())?;
        if let Some(topology) = topology {
            let excluding = self.molecules.exclude_bonded;
            builder = builder.topology(topology).exclude_bonded(excluding);
        }
        if let Some(k) = physics.shear_rate {
            builder = builder.shear_rate(k);
        }
        if let Some(g) = physics.body_force {
            builder = builder.body_force(Vec3::new(g, 0.0, 0.0));
        }
        builder
            .momenta(p)
            .build()
            .map_err(|e| name_bond(e, &bond_ids))
    }

    /// The scene's chains resolved (none without `[[molecules]]`), every molecules key
    /// checked; chains are refused with `[walls]`, `shear_rate` and `init`.
    pub fn chain_plans(&self) -> Result<Vec<ChainPlan>, ParamError> {
        let (particles, names) = (self.geometry.particles(), self.type_names(1));
        let counts = self.type_counts()?;
        let cx = Context {
            species: &names,
            counts: &counts,
            kbt: self.physics.kbt,
            shortest_edge: self.geometry.shortest_edge()?,
        };
        let plans = self.molecules.plan(particles, &cx)?;
        if !plans.is_empty() {
            for (key, set) in [
                ("walls", self.geometry.walls.is_some()),
                ("shear_rate", self.physics.sheared()),
            ] {
                let why = "cannot be combined with [[molecules]] yet";
                check::require(key, "set", !set, why)?;
            }
        }
        Ok(plans)
    }

    /// The bonds and angles of the scene's chains (`None` without `[[molecules]]`).
    pub fn topology(&self) -> Result<Option<Topology>, ParamError> {
        let plans = self.chain_plans()?;
        if plans.is_empty() {
            return Ok(None);
        }
        let (bonds, angles) = chains::bonds_and_angles(&plans);
        let topology = TopologyBuilder {
            particles: self.geometry.particles(),
            bond_types: self.molecules.bond_styles()?,
            bonds,
            angle_types: self.molecules.angle_styles()?,
            angles,
        };
        topology.build().map(Some)
    }

    /// The topology of a run from `init`: a data file's (`file`), or the scene's chains laid
    /// over the `frame` of a GSD file, whose bonds (if it has any) must be theirs and whose
    /// types must be their beads'.
    fn init_topology(
        &self,
        file: Option<Topology>,
        frame: &Frame,
    ) -> Result<Option<Topology>, ParamError> {
        let bad = |why: String| {
            ParamError::new("init", self.geometry.init.clone().unwrap_or_default(), why)
        };
        let scene = self.topology()?;
        if file.is_some() {
            if scene.is_some() {
                return Err(bad("brings its own bonds: leave [[molecules]] out".into()));
            }
            return Ok(file);
        }
        let pairs: Vec<[u32; 2]> = scene
            .iter()
            .flat_map(|t| t.bonds().iter().map(|b| [b.i, b.j]))
            .collect();
        if let Some(b) = frame.bonds.as_ref().filter(|b| !b.group.is_empty()) {
            if scene.is_none() {
                return Err(bad(format!(
                    "has {} bonds, whose coefficients a GSD file does not hold: give them \
                     with [[bond_types]] and [[molecules]], or start from a LAMMPS data file",
                    b.group.len()
                )));
            }
            if b.group != pairs {
                return Err(bad("has other bonds than the scene's [[molecules]]".into()));
            }
        }
        if scene.is_some() {
            let plans = self.chain_plans()?;
            let kinds = chains::kinds(&plans, &self.type_counts()?);
            let beads = pairs.iter().map(|p| p[1] as usize + 1).max().unwrap_or(0);
            if let Some(id) = (0..beads).find(|&i| frame.typeid[i] != u32::from(kinds[i])) {
                return Err(bad(format!(
                    "particle {id} is of type {} in the frame, of type {} as a bead of the \
                     scene's chains",
                    frame.typeid[id], kinds[id]
                )));
            }
        }
        Ok(scene)
    }

    /// The particles of each type: the species' counts, or all of them of the one type.
    fn type_counts(&self) -> Result<Vec<usize>, ParamError> {
        let n = self.geometry.particles();
        match self.species.species {
            Some(_) => self.species.counts(n),
            None => Ok(vec![n]),
        }
    }

    /// The pair-force parameters: the physics section's, with the species' pair coefficients.
    pub fn params(&self) -> Result<Params, ParamError> {
        match self.species.species {
            Some(_) => self
                .species
                .coefficients(self.physics.gamma)?
                .apply(self.physics.builder())
                .build(),
            None => self.physics.params(),
        }
    }

    /// The mass of each particle type.
    pub fn type_masses(&self) -> Vec<f64> {
        match self.species.species {
            Some(_) => self.species.masses(self.physics.mass),
            None => vec![self.physics.mass],
        }
    }

    /// The name of each particle type: the species' names, or A, B, ... Z, T26, T27, ...
    /// for the `types` types of a scene without species.
    pub fn type_names(&self, types: usize) -> Vec<String> {
        match self.species.species {
            Some(_) => self.species.names(),
            None => (0..types as u32).map(type_name).collect(),
        }
    }

    /// The names of `sys`'s bond types, for a system of this scene: the scene's
    /// `[[bond_types]]` names, else (a data file's types) "1", "2", ... as the file numbers them.
    pub fn bond_type_names(&self, sys: &System) -> Vec<String> {
        let count = sys.topology().map_or(0, |t| t.bond_types().len());
        let named = self.molecules.bond_types.as_ref();
        named_or_numbered(named.map(|b| b.iter().map(|t| t.name.as_str())), count)
    }

    /// The names of `sys`'s angle types, as [`Scene::bond_type_names`] gives the bonds'.
    pub fn angle_type_names(&self, sys: &System) -> Vec<String> {
        let count = sys.topology().map_or(0, |t| t.angle_types().len());
        let named = self.molecules.angle_types.as_ref();
        named_or_numbered(named.map(|a| a.iter().map(|t| t.name.as_str())), count)
    }

    /// The names a trajectory of `sys` (a system of this scene) gives its types.
    pub fn trajectory_names(&self, sys: &System) -> TypeNames {
        TypeNames {
            particles: self.type_names(sys.params().types()),
            bonds: self.bond_type_names(sys),
        }
    }

    /// Where run trajectories' counters start: the `init` frame's step, time and images, or 0
    /// without `init` or with `init_reset`.
    pub fn origin(&self, dt: f64) -> Result<Origin, ParamError> {
        let geometry = &self.geometry;
        match &geometry.init {
            Some(init) if !geometry.init_reset => {
                let (n, lengths) = (geometry.particles(), geometry.periodic_box()?.lengths());
                let names = self.species.names();
                let start = InitSpec::parse(init)?.read(n, lengths.into(), &names)?;
                Ok(Origin::of_frame(&start.frame, dt))
            }
            _ => Ok(Origin::default()),
        }
    }
}

/// Type `t`'s name: A, B, ... Z, then T26, T27, ...
fn type_name(t: u32) -> String {
    match char::from_u32(u32::from(b'A') + t) {
        Some(c) if t < 26 => c.to_string(),
        _ => format!("T{t}"),
    }
}

/// `named` when it names all `count` types, else "1", "2", ... "count".
fn named_or_numbered<'a>(
    named: Option<impl ExactSizeIterator<Item = &'a str>>,
    count: usize,
) -> Vec<String> {
    match named {
        Some(names) if names.len() == count => names.map(str::to_string).collect(),
        _ => (1..=count).map(|t| t.to_string()).collect(),
    }
}
