//! The state of a DPD system and the caches that let sub-flows share evaluations.

use crate::bonded::{Located, Overstretch, Topology};
use crate::boundary::{LeesEdwards, PeriodicBox};
use crate::error::{finite_vectors, ParamError};
use crate::neighbour::VerletList;
use crate::pairs::{Excluding, Exclusions, PairTable};
use crate::parallel::on_all_threads;
use crate::params::Params;
use crate::stamp::{Generation, Stamp};
use crate::walls::{FrozenWalls, Walls};
use crate::{Tensor, Vec3};
use dpd_ir::ForceGroup;
use rayon::prelude::*;

/// Default Verlet skin in units of length: 0, cell lists rebuilt every step, which measured
/// faster than a skin of 0.3 at every N tried (500 to 24 000) at the usual steps (docs/
/// performance.md, "Neighbour skin"); a skin pays only when particles move little per step.
pub const DEFAULT_SKIN: f64 = 0.0;

/// How many evaluations the system has done, per force group; the generated schemes are
/// checked against these ([`dpd_ir::Evaluations`] counts the same per step).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counters {
    /// Evaluations of the interacting pairs and their geometry.
    pub pair_distance_evaluations: u64,
    /// Evaluations of the pair forces: per-particle sums (conservative for B and B[pair],
    /// full for F and F[pair]) and the inline pair conservative forces of T sweeps.
    pub force_evaluations: u64,
    /// Evaluations of the bonded forces (for B, F and B[bond]); a system without a topology
    /// evaluates none.
    pub bonded_force_evaluations: u64,
}

/// Positions, momenta, masses and types of N particles in a periodic box (optionally with
/// Lees-Edwards sliding boundaries), the interaction parameters, the time step and the
/// random-number key, plus evaluation caches.
///
/// Particles are stored in the cell order of the neighbour grid and re-sorted at every
/// neighbour-list build (see [`crate::neighbour`]): every per-particle array (positions,
/// momenta, masses, types, [`System::ids`], frozen flags) is permuted together, and
/// [`System::ids`] tells which particle is where. The pair random numbers are keyed by ids, so
/// the noise a pair receives does not depend on where its particles are stored.
///
/// Caches are tied to the positions: the pair geometry, the conservative forces and the full
/// forces (with their noise) are computed at most once per set of positions and are dropped by
/// every drift. The full-force cache is deliberately *not* dropped when momenta change: that is
/// the velocity Verlet convention (forces evaluated at the end of a step are reused for the
/// first half-kick of the next).
#[derive(Clone, Debug)]
pub struct System {
    bx: PeriodicBox,
    /// Lees-Edwards boundaries; `None` is the plain periodic box, whose code paths never look
    /// at shear.
    shear: Option<LeesEdwards>,
    /// Walls across z with their frozen particles; `None`: no walls, and no code path looks
    /// at them.
    walls: Option<FrozenWalls>,
    /// External force on every mobile particle (Poiseuille flow), added to the conservative
    /// and full forces.
    body_force: Option<Vec3>,
    /// Bonds and angles, by id and in storage indices; `None`: no topology, and no code path
    /// looks at bonds.
    bonded: Option<Located>,
    /// The pairs without pair forces (the bonded ones, when the system excludes them);
    /// `None`: every pair within the cut-off interacts, and no fill looks at exclusions.
    exclusions: Option<Exclusions>,
    params: Params,
    q: Vec<Vec3>,
    p: Vec<Vec3>,
    mass: Vec<f64>,
    inv_mass: Vec<f64>,
    kind: Vec<u16>,
    /// Identity of each stored particle: its index at construction.
    id: Vec<u32>,
    dt: f64,
    seed: u64,
    step: u64,
    list: VerletList,
    /// Generation of the positions, advanced by every change of them (see [`crate::stamp`]).
    positions: Generation,
    pairs: PairTable,
    pairs_at: Stamp,
    conservative: Vec<Vec3>,
    conservative_at: Stamp,
    full: Vec<Vec3>,
    full_at: Stamp,
    /// Whether a pair sweep that finds the pair table stale fills it while summing the
    /// conservative forces, for a scheme that kicks with them after the sweep at the same
    /// positions ([`System::ensure_sweep_pairs`]).
    sweeps_fill_forces: bool,
    /// Bonded forces (empty without a topology).
    bonded_forces: Vec<Vec3>,
    bonded_at: Stamp,
    /// The first bond an evaluation of the step under way found beyond its reach.
    overstretch: Option<Overstretch>,
    /// Pair virial of the dissipative and random parts of `full`, when impulses were being
    /// recorded as it was evaluated.
    full_virial: Option<Tensor>,
    /// Pair impulses of the dissipative and random forces being recorded for the stress
    /// (`None`: not recording, and the sweeps do not pay for it).
    impulses: Option<ImpulseVirial>,
    /// Heat taken up from the thermostat since recording started: the sum of the kinetic
    /// energy changes of the O and O-BBK sweeps (`None`: not recording, and the sweeps do not
    /// pay for it; see [`crate::observe::EnergyBalance`]).
    heat: Option<f64>,
    /// PAdL's adaptive friction factor: Oa sweeps with friction `xi gamma_ij`, Xi moves it
    /// (module `crate::flow`). Dimensionless; at construction 1, where Oa is O, or 0 with a
    /// thermostat friction (PNHL, whose xi centres on 0).
    xi: f64,
    /// What the `{` of a Metropolis-adjusted part kept, and the potential energy it reuses.
    proposal: Proposal,
    /// The accept/reject tests of Metropolis-adjusted parts so far (checkpointed).
    acceptance: Acceptance,
    counters: Counters,
    /// Largest single-particle drift length summed over the drifts since the neighbour list
    /// last checked the positions (length units; NaN once a drift length was NaN).
    travel: f64,
    /// Largest value `travel` reached during this step: a bound on how far a particle moved
    /// between two checks of the neighbour list.
    drift_bound: f64,
    /// The undo copy of the guarded step, kept to reuse its allocations.
    backup: Backup,
}

mod adjusted;
mod bonds;
mod builder;
mod forces;
mod guard;
mod records;
mod resume;
mod views;

pub use adjusted::Acceptance;
use adjusted::Proposal;
pub use builder::SystemBuilder;
use guard::Backup;
pub(crate) use records::ImpulseVirial;
pub(crate) use resume::Continuation;
pub(crate) use views::{Motion, PairState};

impl System {
    pub fn len(&self) -> usize {
        self.q.len()
    }
    pub fn is_empty(&self) -> bool {
        self.q.is_empty()
    }
    pub fn params(&self) -> &Params {
        &self.params
    }
    pub fn boundary(&self) -> &PeriodicBox {
        &self.bx
    }
    /// The Lees-Edwards boundaries, if the box is sheared.
    pub fn shear(&self) -> Option<&LeesEdwards> {
        self.shear.as_ref()
    }
    /// The walls, if any.
    pub fn walls(&self) -> Option<&Walls> {
        self.walls.as_ref().map(|w| &w.walls)
    }
    /// Which particles are frozen (`None` without walls).
    pub fn frozen(&self) -> Option<&[bool]> {
        self.walls.as_ref().map(|w| &w.frozen[..])
    }
    /// The bonds and angles, by particle id, if the system was built with a topology.
    pub fn topology(&self) -> Option<&Topology> {
        self.bonded.as_ref().map(Located::topology)
    }
    /// Whether bonded pairs are left out of the pair forces ([`SystemBuilder::exclude_bonded`]).
    pub fn excludes_bonded(&self) -> bool {
        self.exclusions.is_some()
    }
    /// The bonds and angles in storage indices.
    #[cfg(test)]
    pub(crate) fn located(&self) -> Option<&Located> {
        self.bonded.as_ref()
    }
    /// The external force on mobile particles, if any.
    pub fn body_force(&self) -> Option<Vec3> {
        self.body_force
    }
    pub fn positions(&self) -> &[Vec3] {
        &self.q
    }
    pub fn momenta(&self) -> &[Vec3] {
        &self.p
    }
    pub fn masses(&self) -> &[f64] {
        &self.mass
    }
    /// Inverse masses, 0 for frozen particles.
    pub(crate) fn inverse_masses(&self) -> &[f64] {
        &self.inv_mass
    }
    pub fn kinds(&self) -> &[u16] {
        &self.kind
    }
    /// Identity of each stored particle (its index at construction); the storage order
    /// changes at neighbour-list builds, the identities travel with the particles.
    pub fn ids(&self) -> &[u32] {
        &self.id
    }
    /// Time step.
    pub fn dt(&self) -> f64 {
        self.dt
    }
    /// Change the time step between steps (a dt sweep from one state, as HOOMD's
    /// `integrator.dt`). The cached full forces are dropped: their random part is scaled by the
    /// time step they were drawn for.
    pub fn set_dt(&mut self, dt: f64) -> Result<(), ParamError> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(ParamError::new("dt", dt, "must be finite and > 0"));
        }
        self.dt = dt;
        self.full_at = Stamp::default();
        Ok(())
    }
    /// PAdL's and PNHL's adaptive friction factor `xi` (dimensionless; 1, or 0 with a
    /// thermostat friction, until an Xi stage moves it).
    pub fn xi(&self) -> f64 {
        self.xi
    }
    /// Set the adaptive friction factor (a restart, or a chosen start); must be finite.
    pub fn set_xi(&mut self, xi: f64) -> Result<(), ParamError> {
        if !xi.is_finite() {
            return Err(ParamError::new("xi", xi, "must be finite"));
        }
        self.xi = xi;
        Ok(())
    }
    /// Key of the pair random numbers.
    pub fn seed(&self) -> u64 {
        self.seed
    }
    /// Number of completed steps.
    pub fn step(&self) -> u64 {
        self.step
    }
    pub fn counters(&self) -> Counters {
        self.counters
    }
    /// Neighbour skin (length): the list holds the pairs within `r_c + skin`.
    pub fn skin(&self) -> f64 {
        self.list.skin()
    }
    /// The force groups the system has, each a part of the forces a scheme may kick on its own
    /// (`B[pair]`, `B[bond]`): the pair forces, and the bonded forces when the topology has
    /// some bond or angle.
    pub fn force_groups(&self) -> &[ForceGroup] {
        if self.has_bonded_forces() {
            &ForceGroup::ALL
        } else {
            &[ForceGroup::Pair]
        }
    }
    /// Number of neighbour-list builds so far.
    pub fn list_builds(&self) -> u64 {
        self.list.builds()
    }

    /// Kinetic energy `sum_i p_i . p_i / (2 m_i)` (frozen particles count 0).
    pub fn kinetic_energy(&self) -> f64 {
        0.5 * self
            .p
            .iter()
            .zip(&self.inv_mass)
            .map(|(p, im)| p.norm_squared() * im)
            .sum::<f64>()
    }

    /// Total momentum.
    pub fn total_momentum(&self) -> Vec3 {
        self.p.iter().sum()
    }

    /// Mutable momenta. Positions and the caches tied to them are unaffected.
    pub fn momenta_mut(&mut self) -> &mut [Vec3] {
        &mut self.p
    }

    /// Replace positions (wrapped into the box); drops every position-dependent cache.
    pub fn set_positions(&mut self, q: &[Vec3]) -> Result<(), ParamError> {
        if q.len() != self.q.len() {
            return Err(ParamError::new(
                "positions",
                format!("{} entries", q.len()),
                format!("must have {} entries", self.q.len()),
            ));
        }
        finite_vectors("positions", q)?;
        self.place(q);
        self.positions_changed();
        Ok(())
    }

    /// Set positions to `q` wrapped into the box; under Lees-Edwards a particle brought in
    /// across the y boundary takes the image's x-velocity too (see [`LeesEdwards::wrap`]).
    fn place(&mut self, q: &[Vec3]) {
        match self.shear {
            None => {
                for (dst, &x) in self.q.iter_mut().zip(q) {
                    *dst = self.bx.wrap(x);
                }
            }
            Some(le) => {
                let kick = le.image_velocity(&self.bx);
                for (((dst, p), m), &x) in self.q.iter_mut().zip(&mut self.p).zip(&self.mass).zip(q)
                {
                    let (wrapped, n) = le.wrap(&self.bx, x);
                    *dst = wrapped;
                    p.x -= n * m * kick;
                }
            }
        }
    }

    /// Start a new generation of the positions: every cache tied to them is stale.
    pub(crate) fn positions_changed(&mut self) {
        self.positions.advance();
        self.list.positions_changed();
    }

    /// The interacting pairs at the current positions, in the sweep order documented in
    /// [`crate::neighbour`] (evaluated if needed). Evaluating them may rebuild the neighbour
    /// list, which re-sorts the particles: read positions and momenta after this call, and
    /// the pair indices `i`, `j` are storage indices (see [`System::ids`]).
    pub fn pairs(&mut self) -> &PairTable {
        self.ensure_pairs();
        &self.pairs
    }

    /// Conservative forces `F^C_i` at the current positions (evaluated if needed).
    pub fn conservative_forces(&mut self) -> &[Vec3] {
        self.ensure_conservative();
        &self.conservative
    }

    pub(crate) fn ensure_pairs(&mut self) {
        if !self.pairs_at.is_fresh(self.positions) {
            self.prepare_list();
            self.pairs.collect(
                &self.list,
                &self.q,
                &self.bx,
                self.shear.as_ref(),
                self.walls.as_ref(),
                &self.params,
                &self.kind,
                Excluding::of(self.exclusions.as_ref(), &self.id),
            );
            self.pairs_filled();
        }
    }

    /// Call `f` with the pairs and conservative forces of the current positions, for
    /// observables, without changing when the neighbour list is rebuilt (the sweep order
    /// depends on the rebuild times, so measuring must not move them): when the list is
    /// due for a rebuild, a scratch list is used and nothing is cached.
    pub(crate) fn with_forces<R>(
        &mut self,
        f: impl FnOnce(&System, &PairTable, &[Vec3]) -> R,
    ) -> R {
        let shear = self.shear.as_ref();
        if self.pairs_at.is_fresh(self.positions)
            || !self.list.needs_rebuild(&self.q, &self.bx, shear)
        {
            self.ensure_conservative();
            return f(self, &self.pairs, &self.conservative);
        }
        // A copy, sorted and listed on its own (without skin, nothing but the pairs). What the
        // copy would only overwrite (list, pairs, stale conservative forces, the undo copy) is
        // set aside rather than cloned.
        let list = std::mem::replace(&mut self.list, VerletList::new(0.0));
        let pairs = std::mem::take(&mut self.pairs);
        let conservative = std::mem::take(&mut self.conservative);
        let backup = std::mem::take(&mut self.backup);
        let mut scratch = self.clone();
        (self.list, self.pairs, self.conservative, self.backup) =
            (list, pairs, conservative, backup);
        scratch.ensure_conservative();
        f(&scratch, &scratch.pairs, &scratch.conservative)
    }

    /// Count a fill of the pair table from the current positions, which is now valid.
    fn pairs_filled(&mut self) {
        self.pairs_at = Stamp::at(self.positions);
        self.counters.pair_distance_evaluations += 1;
    }

    /// Rebuild the neighbour list if the positions call for it. Either way the list has now
    /// checked the positions, and the travel since the last check starts again.
    fn prepare_list(&mut self) {
        if self
            .list
            .needs_rebuild(&self.q, &self.bx, self.shear.as_ref())
        {
            self.rebuild_list();
        }
        self.travel = 0.0;
    }

    /// Re-sort the particles into the cell order of a fresh grid and build the list on them.
    fn rebuild_list(&mut self) {
        let order = self.list.bin(&self.q, &self.bx, self.params.rc());
        permute(&mut self.q, order);
        permute(&mut self.p, order);
        permute(&mut self.mass, order);
        permute(&mut self.inv_mass, order);
        permute(&mut self.kind, order);
        permute(&mut self.id, order);
        if let Some(w) = &mut self.walls {
            permute(&mut w.frozen, order);
            permute(&mut w.velocity_x, order);
        }
        if let Some(b) = &mut self.bonded {
            b.permute(order);
        }
        // Positions changed or the list was never built: the conservative forces are stale;
        // full forces can be valid (restored from a checkpoint) and move with their particles.
        debug_assert!(!self.conservative_at.is_fresh(self.positions));
        if self.full_at.is_fresh(self.positions) {
            permute(&mut self.full, order);
        }
        if self.bonded_at.is_fresh(self.positions) {
            permute(&mut self.bonded_forces, order);
        }
        self.list
            .build(&self.q, &self.bx, self.shear.as_ref(), self.params.rc());
    }

    /// Put the particles back into the storage order of `ids` (a permutation of the current
    /// ids), e.g. the order before a step that is being undone. Positions, momenta and the
    /// caches are left to the caller; the list is dropped.
    pub(crate) fn restore_order(&mut self, ids: &[u32]) {
        if self.id == ids {
            return;
        }
        let mut at = vec![0u32; self.id.len()];
        for (k, &i) in self.id.iter().enumerate() {
            at[i as usize] = k as u32;
        }
        let order: Vec<u32> = ids.iter().map(|&i| at[i as usize]).collect();
        permute(&mut self.mass, &order);
        permute(&mut self.inv_mass, &order);
        permute(&mut self.kind, &order);
        permute(&mut self.id, &order);
        if let Some(w) = &mut self.walls {
            permute(&mut w.frozen, &order);
            permute(&mut w.velocity_x, &order);
        }
        if let Some(b) = &mut self.bonded {
            b.locate(&self.id);
        }
        self.list.invalidate();
    }
}

/// `v[k] <- v[order[k]]`.
fn permute<T: Copy + Send + Sync>(v: &mut Vec<T>, order: &[u32]) {
    let sorted: Vec<T> = if on_all_threads(v.len()) {
        order.par_iter().map(|&i| v[i as usize]).collect()
    } else {
        order.iter().map(|&i| v[i as usize]).collect()
    };
    *v = sorted;
}
