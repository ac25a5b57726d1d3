//! [`SystemBuilder`]: the validated construction of a [`System`].

use super::{Counters, System, DEFAULT_SKIN};
use crate::bonded::{Located, Topology};
use crate::boundary::{LeesEdwards, PeriodicBox};
use crate::error::{finite_vectors, positive, ParamError};
use crate::neighbour::VerletList;
use crate::pairs::{Exclusions, PairTable};
use crate::params::Params;
use crate::stamp::{Generation, Stamp};
use crate::walls::{FrozenWalls, Walls};
use crate::Vec3;

/// Builds a [`System`]; every input is validated by [`SystemBuilder::build`].
#[derive(Clone, Debug)]
pub struct SystemBuilder {
    params: Params,
    bx: PeriodicBox,
    q: Vec<Vec3>,
    p: Option<Vec<Vec3>>,
    mass: Option<Vec<f64>>,
    kind: Option<Vec<u16>>,
    id: Option<Vec<u32>>,
    dt: f64,
    seed: u64,
    skin: f64,
    shear_rate: Option<f64>,
    walls: Option<Walls>,
    frozen: Option<Vec<bool>>,
    body_force: Option<Vec3>,
    topology: Option<Topology>,
    exclude_bonded: bool,
}

impl SystemBuilder {
    /// Momenta (default: all zero).
    pub fn momenta(mut self, p: Vec<Vec3>) -> Self {
        self.p = Some(p);
        self
    }
    /// Per-particle masses (default: all 1).
    pub fn masses(mut self, m: Vec<f64>) -> Self {
        self.mass = Some(m);
        self
    }
    /// Per-particle types, indices into the `a` matrix (default: all 0).
    pub fn kinds(mut self, k: Vec<u16>) -> Self {
        self.kind = Some(k);
        self
    }
    /// Particle identities, a permutation of `0..N` (default: `0, 1, ..., N - 1`): a checkpoint
    /// restores them with the particles in their stored order.
    pub fn ids(mut self, id: Vec<u32>) -> Self {
        self.id = Some(id);
        self
    }
    pub fn dt(mut self, dt: f64) -> Self {
        self.dt = dt;
        self
    }
    pub fn seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }
    pub fn skin(mut self, skin: f64) -> Self {
        self.skin = skin;
        self
    }
    /// Lees-Edwards boundaries with shear rate `kappa` (flow along x, gradient along y; see
    /// [`LeesEdwards`]). Without this call the box is plain periodic; with `kappa = 0` the run
    /// is bitwise the periodic one, through the sliding-boundary code.
    pub fn shear_rate(mut self, kappa: f64) -> Self {
        self.shear_rate = Some(kappa);
        self
    }
    /// Walls across z bounding the channel `lower <= z <= upper` (see [`crate::walls`]); mobile
    /// particles must start inside it.
    pub fn walls(mut self, walls: Walls) -> Self {
        self.walls = Some(walls);
        self
    }
    /// Which particles are frozen wall particles (default: none); needs [`Self::walls`].
    pub fn frozen(mut self, frozen: Vec<bool>) -> Self {
        self.frozen = Some(frozen);
        self
    }
    /// A constant external force on every mobile particle (force units), e.g. the driving of
    /// Poiseuille flow. It enters the B and F kicks and the T sweeps (after the pair updates).
    pub fn body_force(mut self, force: Vec3) -> Self {
        self.body_force = Some(force);
        self
    }
    /// Bonds and angles between the particles, by id (see [`Topology`]); its particle count
    /// must be the system's. Without this call the system has no bonded forces.
    pub fn topology(mut self, topology: Topology) -> Self {
        self.topology = Some(topology);
        self
    }
    /// Leave the bonded pairs out of the pair forces (`true`), as LAMMPS's `special_bonds lj 0 1
    /// 1` does with `pair_style dpd`: two beads joined by a bond then have no conservative,
    /// dissipative or random pair force, only the bond's. Default `false`: bonded beads keep
    /// their soft repulsion (the DPD convention). Needs [`Self::topology`].
    pub fn exclude_bonded(mut self, exclude: bool) -> Self {
        self.exclude_bonded = exclude;
        self
    }
    pub fn build(self) -> Result<System, ParamError> {
        let n = self.q.len();
        if n < 2 {
            return Err(ParamError::new(
                "positions",
                format!("{n} particles"),
                "needs at least 2 particles",
            ));
        }
        if n > u32::MAX as usize {
            return Err(ParamError::new(
                "positions",
                format!("{n} particles"),
                "at most 2^32 - 1 particles",
            ));
        }
        let p = self.p.unwrap_or_else(|| vec![Vec3::zeros(); n]);
        let mass = self.mass.unwrap_or_else(|| vec![1.0; n]);
        let kind = self.kind.unwrap_or_else(|| vec![0; n]);
        let id = self.id.unwrap_or_else(|| (0..n as u32).collect());
        for (name, len) in [
            ("momenta", p.len()),
            ("masses", mass.len()),
            ("kinds", kind.len()),
            ("ids", id.len()),
        ] {
            if len != n {
                return Err(ParamError::new(
                    name,
                    format!("{len} entries"),
                    format!("must have one entry per particle ({n})"),
                ));
            }
        }
        let mut seen = vec![false; n];
        for (k, &i) in id.iter().enumerate() {
            if i as usize >= n || std::mem::replace(&mut seen[i as usize], true) {
                return Err(ParamError::new(
                    format!("ids[{k}]"),
                    i,
                    format!("ids must be a permutation of 0..{n}: each of 0..{n} exactly once"),
                ));
            }
        }
        finite_vectors("positions", &self.q)?;
        finite_vectors("momenta", &p)?;
        for (i, &m) in mass.iter().enumerate() {
            positive(&format!("mass[{i}]"), m)?;
        }
        for (i, &k) in kind.iter().enumerate() {
            if k as usize >= self.params.types() {
                return Err(ParamError::new(
                    format!("kinds[{i}]"),
                    k,
                    format!("must be < {} (rows of a)", self.params.types()),
                ));
            }
        }
        let dt = positive("dt", self.dt)?;
        if !(self.skin.is_finite() && self.skin >= 0.0) {
            return Err(ParamError::new(
                "skin",
                self.skin,
                "must be finite and >= 0",
            ));
        }
        let reach = self.params.rc() + self.skin;
        if self.bx.min_length() < 2.0 * reach {
            return Err(ParamError::new(
                "box",
                format!("{:?}", <[f64; 3]>::from(self.bx)),
                format!("every edge must be at least 2 (r_c + skin) = {} for the minimum-image convention", 2.0 * reach),
            ));
        }
        let shear = self.shear_rate.map(LeesEdwards::new).transpose()?;
        if let Some(g) = self.body_force {
            if !g.iter().all(|x| x.is_finite()) {
                return Err(ParamError::new(
                    "body_force",
                    format!("{g:?}"),
                    "must be finite",
                ));
            }
        }
        let walls = match (self.walls, self.frozen) {
            (None, None) => None,
            (None, Some(_)) => {
                return Err(ParamError::new(
                    "frozen",
                    "frozen particles without walls",
                    "frozen particles belong to walls: set the walls too",
                ))
            }
            (Some(w), frozen) => {
                if shear.is_some() {
                    return Err(ParamError::new(
                        "shear_rate",
                        self.shear_rate.unwrap_or_default(),
                        "Lees-Edwards shear needs a box periodic along z; it cannot be combined \
                         with walls (drive wall-bounded shear by moving the walls instead)",
                    ));
                }
                w.check(&self.bx, self.params.rc())?;
                let frozen = frozen.unwrap_or_else(|| vec![false; n]);
                if frozen.len() != n {
                    return Err(ParamError::new(
                        "frozen",
                        format!("{} entries", frozen.len()),
                        format!("must have one entry per particle ({n})"),
                    ));
                }
                let q: Vec<Vec3> = self.q.iter().map(|&x| self.bx.wrap(x)).collect();
                Some(FrozenWalls::new(w, frozen, &q)?)
            }
        };
        if let Some(t) = &self.topology {
            if t.particles() != n {
                return Err(ParamError::new(
                    "topology",
                    format!("{} particles", t.particles()),
                    format!("must be built for the system's {n} particles"),
                ));
            }
        }
        let exclusions = match (&self.topology, self.exclude_bonded) {
            (_, false) => None,
            (None, true) => {
                return Err(ParamError::new(
                    "exclude_bonded",
                    true,
                    "needs a topology: a system without bonds has no bonded pairs to exclude",
                ))
            }
            (Some(t), true) => {
                let bonds = t.bonds().iter().map(|b| (b.i, b.j));
                Some(Exclusions::of_pairs(n, bonds))
            }
        };
        let bonded = self.topology.map(|t| Located::new(t, &id));
        let inv_mass = match &walls {
            None => mass.iter().map(|m| 1.0 / m).collect(),
            Some(w) => mass
                .iter()
                .zip(&w.frozen)
                .map(|(m, &f)| if f { 0.0 } else { 1.0 / m })
                .collect(),
        };
        // xi starts at the mean of its invariant measure: 1 for PAdL, 0 for PNHL (a thermostat
        // friction set), where a start at 1 is a friction of gamma_ij the feedback must undo.
        let xi = match self.params.thermostat_friction() {
            Some(_) => 0.0,
            None => 1.0,
        };
        let mut sys = System {
            bx: self.bx,
            shear,
            walls,
            body_force: self.body_force,
            bonded,
            exclusions,
            params: self.params,
            q: vec![Vec3::zeros(); n],
            p,
            mass,
            inv_mass,
            kind,
            id,
            dt,
            seed: self.seed,
            step: 0,
            list: VerletList::new(self.skin),
            positions: Generation::default(),
            pairs: PairTable::default(),
            pairs_at: Stamp::default(),
            conservative: Vec::new(),
            conservative_at: Stamp::default(),
            full: Vec::new(),
            full_at: Stamp::default(),
            sweeps_fill_forces: false,
            bonded_forces: Vec::new(),
            bonded_at: Stamp::default(),
            overstretch: None,
            full_virial: None,
            impulses: None,
            heat: None,
            xi,
            proposal: Default::default(),
            acceptance: Default::default(),
            counters: Counters::default(),
            travel: 0.0,
            drift_bound: 0.0,
            backup: Default::default(),
        };
        sys.place(&self.q);
        sys.check_bond_lengths()?;
        Ok(sys)
    }
}

impl System {
    /// Start building a system of particles at `positions` (wrapped into the box).
    pub fn builder(params: Params, bx: PeriodicBox, positions: Vec<Vec3>) -> SystemBuilder {
        SystemBuilder {
            params,
            bx,
            q: positions,
            p: None,
            mass: None,
            kind: None,
            id: None,
            dt: 0.01,
            seed: 0,
            skin: DEFAULT_SKIN,
            shear_rate: None,
            walls: None,
            frozen: None,
            body_force: None,
            topology: None,
            exclude_bonded: false,
        }
    }
}
