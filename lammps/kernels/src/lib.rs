//! The physics of the LAMMPS plugin `fix dpd/split` (see `docs/lammps.md`): a small C ABI over
//! dpd-core's pairwise sweeps, so that the plugin's C++ only moves data and the pair updates,
//! pair weights and pair noise are those of `dpd run`.
//!
//! The plugin hands a sweep a list of `(i, j)` pairs, indices into LAMMPS's per-atom arrays
//! (owned atoms and ghost copies), and the arrays as LAMMPS stores them ([`Atoms`]). The pairs
//! are applied one after the other in the given order (or reversed), each to the current
//! velocities of both atoms, as in dpd-core's sweeps (algorithms.md section 2): `u = e_ij .
//! (v_i - v_j)`, `impulse = slope u + offset`, `v_i += impulse e_ij / m_i`, `v_j -= impulse
//! e_ij / m_j`. Friction and cutoff are per pair of atom types, as `pair dpd`'s are: a pair of
//! types `(I, J)` has `gamma_IJ`, `sigma_IJ^2 = 2 gamma_IJ k_B T` and weights `w_D = w_R^2 =
//! (1 - r/r_c,IJ)^s`; pairs at `r >= r_c,IJ` are skipped. The T sweep includes the pair's
//! conservative force, that of the plugin's pair style `dpd/soft` ([`soft::SoftStyle`]), in
//! its exact update. The normal of a pair is dpd-core's Philox pair normal keyed by
//! `(seed, step, stream, min(tag), max(tag))`, so each pair gets the same numbers whatever the
//! decomposition of the box over ranks.
//!
//! Licensed MIT (not MIT OR Apache-2.0 like the rest of the workspace): it is linked into a
//! plugin of LAMMPS, which is GPLv2, and MIT is compatible with it.

pub mod abi;
pub mod atoms;
pub mod record;
pub mod soft;

pub use atoms::{Atoms, Tags};
use dpd_core::flow::{bbk_update, ou_update, ou_updates, trotter_update, Change};
use dpd_core::force::full_pair_force;
use dpd_core::rng::pair_normal;
use dpd_core::Params;
use record::PairRecord;
use soft::SoftStyle;
use std::ffi::c_int;

/// Pairs per chunk of a sweep ([`Kernels::sweep_pairs`]): the chunk's geometry, normals and
/// changes (96 bytes a pair, 24 KiB) stay in the L1 cache between its passes.
const CHUNK: usize = 256;

/// One pair within its cutoff `r_c,IJ`: atoms i and j, `e_ij = (x_i - x_j) / r`, the distance
/// `r`, the weight `w = 1 - r / r_c,IJ` and the type pair's slot `I (ntypes + 1) + J` in the
/// kernels' tables.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Near {
    i: usize,
    j: usize,
    e: [f64; 3],
    r: f64,
    w: f64,
    slot: usize,
}

/// The per-chunk buffers of a sweep, kept from chunk to chunk: the pairs within their cutoff,
/// their normals and their changes.
#[derive(Default)]
struct Scratch {
    near: Vec<Near>,
    z: Vec<f64>,
    changes: Vec<Change>,
}

/// Which pairwise sweep [`Kernels::sweep`] applies.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SweepFlow {
    /// O: the exact pairwise Ornstein-Uhlenbeck update.
    Ou = 0,
    /// Ob: Shardlow's BBK update.
    Bbk = 1,
    /// T: the exact pair update with the pair's conservative force included (DPD-Trotter).
    Trotter = 2,
}

/// One pairwise sweep: its flow, step length `h`, noise key `(seed, step, stream)` and
/// direction (`reverse`: the pairs last to first).
#[derive(Clone, Copy, Debug)]
pub struct Sweep {
    pub flow: SweepFlow,
    pub h: f64,
    pub key: (u64, u64, u8),
    pub reverse: bool,
}

/// Status of a call: 0 for success, else what was wrong.
pub const DPD_LAMMPS_OK: c_int = 0;
/// A null pointer where an array or handle was required.
pub const DPD_LAMMPS_NULL: c_int = 1;
/// A pair index at or beyond the number of atoms given.
pub const DPD_LAMMPS_INDEX: c_int = 2;
/// A flow code that is not a [`SweepFlow`], or a stream outside 0..=255.
pub const DPD_LAMMPS_FLOW: c_int = 3;
/// A tag (global atom id) outside `0..=u32::MAX`, or a tag width other than 4 or 8 bytes.
pub const DPD_LAMMPS_TAG: c_int = 4;
/// A T sweep without the conservative style.
pub const DPD_LAMMPS_STYLE: c_int = 5;
/// An atom type outside `1..=ntypes`.
pub const DPD_LAMMPS_TYPE: c_int = 6;

/// The friction and cutoff of one pair of atom types: `gamma`, `sigma = sqrt(2 gamma k_B T)`
/// and `r_c`, validated by dpd-core ([`Params`]).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Coefficients {
    gamma: f64,
    sigma: f64,
    rc: f64,
}

/// The sweep parameters of one fix: `k_B T`, the weight exponent, and per pair of the
/// `ntypes` atom types its [`Coefficients`], at `I * (ntypes + 1) + J` (row and column 0
/// unused, as LAMMPS's type arrays).
pub struct Kernels {
    kbt: f64,
    /// The weight `w_R` of the exponent (the same for every pair).
    weights: Params,
    ntypes: usize,
    pairs: Vec<Coefficients>,
    /// Whether some pair has friction (else O and Ob do nothing).
    friction: bool,
    /// The friction of every type pair when it is the same for all (then O computes the pair
    /// updates several at a time, [`ou_updates`]).
    uniform_gamma: Option<f64>,
}

/// The conservative force a T sweep includes: the `dpd/soft` coefficients.
pub type Conservative<'a> = SoftStyle<'a>;

impl Kernels {
    /// Validated parameters for `ntypes` types with per type-pair `gamma` and `rc`
    /// (`(ntypes + 1)^2` values each, symmetric), or dpd-core's message naming the bad field,
    /// its value and what is allowed, and the type pair.
    pub fn new(
        kbt: f64,
        exponent: f64,
        ntypes: usize,
        gamma: &[f64],
        rc: &[f64],
    ) -> Result<Kernels, String> {
        let n = ntypes + 1;
        if ntypes == 0 || gamma.len() < n * n || rc.len() < n * n {
            return Err(format!(
                "ntypes = {ntypes} with {} gamma and {} r_c values: need ntypes >= 1 and \
                 (ntypes + 1)^2 values each",
                gamma.len(),
                rc.len()
            ));
        }
        let mut pairs = vec![
            Coefficients {
                gamma: 0.0,
                sigma: 0.0,
                rc: 0.0
            };
            n * n
        ];
        let mut weights = None;
        for i in 1..n {
            for j in 1..n {
                let (k, mirror) = (i * n + j, j * n + i);
                if gamma[k] != gamma[mirror] || rc[k] != rc[mirror] {
                    return Err(format!(
                        "type pair {i} {j}: gamma {} and r_c {} differ from those of {j} {i} \
                         ({} and {}); they must be symmetric",
                        gamma[k], rc[k], gamma[mirror], rc[mirror]
                    ));
                }
                let params = Params::builder()
                    .gamma(gamma[k])
                    .kbt(kbt)
                    .rc(rc[k])
                    .weight_exponent(exponent)
                    .build()
                    .map_err(|e| format!("type pair {i} {j}: {e}"))?;
                pairs[k] = Coefficients {
                    gamma: params.gamma(),
                    sigma: params.sigma(),
                    rc: params.rc(),
                };
                weights.get_or_insert(params);
            }
        }
        let friction = pairs.iter().any(|c| c.gamma > 0.0);
        let first = pairs[n + 1].gamma;
        let uniform = (1..n).all(|i| (1..n).all(|j| pairs[i * n + j].gamma == first));
        Ok(Kernels {
            kbt,
            weights: weights.expect("ntypes >= 1"),
            ntypes,
            pairs,
            friction,
            uniform_gamma: uniform.then_some(first),
        })
    }

    /// One type with friction `gamma` and cutoff `rc`.
    pub fn uniform(gamma: f64, kbt: f64, rc: f64, exponent: f64) -> Result<Kernels, String> {
        Kernels::new(
            kbt,
            exponent,
            1,
            &[0.0, 0.0, 0.0, gamma],
            &[0.0, 0.0, 0.0, rc],
        )
    }

    /// The number of atom types.
    pub fn ntypes(&self) -> usize {
        self.ntypes
    }

    /// The cutoff of each type-pair slot (see [`Kernels`]).
    pub fn cutoffs(&self) -> Vec<f64> {
        self.pairs.iter().map(|c| c.rc).collect()
    }

    /// The type-pair slot of the pair of atoms `i`, `j` (types checked by [`Atoms::check`]).
    #[inline(always)]
    fn slot(&self, atoms: &Atoms, i: usize, j: usize) -> usize {
        atoms.type_of(i) * (self.ntypes + 1) + atoms.type_of(j)
    }

    /// The coefficients of the pair of atoms `i`, `j` (types checked by [`Atoms::check`]).
    #[inline(always)]
    fn coefficients(&self, atoms: &Atoms, i: usize, j: usize) -> Coefficients {
        self.pairs[self.slot(atoms, i, j)]
    }

    /// The update of the pair `p` with inverse reduced mass `mu`, standard normal `z` and
    /// conservative pair force `f` (used by T only).
    fn change(&self, flow: SweepFlow, h: f64, p: &Near, mu: f64, z: f64, f: f64) -> Change {
        let (c, wr) = (self.pairs[p.slot], self.weights.w_r(p.w));
        match flow {
            SweepFlow::Ou => ou_update(c.gamma, self.kbt, h, wr, mu, z),
            SweepFlow::Bbk => bbk_update(c.gamma, c.sigma, h, h.max(0.0).sqrt(), wr, mu, z),
            SweepFlow::Trotter => trotter_update(c.gamma, self.kbt, h, f, wr, mu, z),
        }
    }

    /// The unit vector `e_ij`, distance `r` and weight `w = 1 - r/r_c` of the pair `(i, j)`
    /// when `0 < r < r_c`.
    #[inline(always)]
    fn geometry(atoms: &Atoms, i: usize, j: usize, rc: f64) -> Option<([f64; 3], f64, f64)> {
        let (d, r2) = atoms.separation(i, j);
        if r2 >= rc * rc || r2 == 0.0 {
            return None;
        }
        let r = r2.sqrt();
        Some((d.map(|c| c / r), r, 1.0 - r / rc))
    }

    /// Apply `sweep` to `pairs` in its order (see the crate documentation); `v` holds `3 n`
    /// doubles; T needs `conservative`, the others ignore it. With `virial`, adds each pair's
    /// `r_ij (x) J_ij` to it ([`add_virial`]), `J_ij` the impulse on atom i less its
    /// conservative part (the pair style's virial holds that).
    /// Returns a `DPD_LAMMPS_*` status; on an error no velocity has changed.
    pub fn sweep(
        &self,
        sweep: Sweep,
        pairs: &[[c_int; 2]],
        atoms: &Atoms,
        v: &mut [f64],
        conservative: Option<&Conservative>,
        virial: Option<&mut [f64; 6]>,
    ) -> c_int {
        let status = atoms.check(pairs, v.len(), self.ntypes);
        if status != DPD_LAMMPS_OK {
            return status;
        }
        self.sweep_pairs(sweep, pairs, atoms, v, conservative, virial)
    }

    /// [`Kernels::sweep`] over the pairs of `record` (a `dpd/soft` evaluation at the current
    /// positions, [`PairRecord`]) of the atoms of colour `colour`: the same updates, bit for
    /// bit, as a sweep over the neighbour list's pairs of those atoms in the list's order,
    /// without passing over the list or the pairs. Returns `DPD_LAMMPS_INDEX` if the record is
    /// not complete, not of these atoms or of kernels of another number of types, or `colour`
    /// is not 0 to 7.
    pub fn sweep_recorded(
        &self,
        sweep: Sweep,
        (colour, record): (usize, &PairRecord),
        atoms: &Atoms,
        v: &mut [f64],
        conservative: Option<&Conservative>,
        virial: Option<&mut [f64; 6]>,
    ) -> c_int {
        let status = atoms.check(&[], v.len(), self.ntypes);
        if status != DPD_LAMMPS_OK {
            return status;
        }
        let Some(pairs) = record.bucket(colour, atoms.len(), self.ntypes) else {
            return DPD_LAMMPS_INDEX;
        };
        self.sweep_pairs(sweep, pairs, atoms, v, conservative, virial)
    }

    /// Apply a sweep to `pairs` (indices below `atoms.len()`, checked with `v` by
    /// [`Atoms::check`]; those beyond their cutoff skipped), `CHUNK` pairs at a time in the
    /// sweep's order, each chunk in four passes so that only the last is a chain of dependent
    /// updates: the pairs within their cutoff and their geometry; their normals, several pairs
    /// at a time (dpd-core's `pair_normals`, bitwise its `pair_normal`); their changes, each
    /// from its own geometry and noise (O with one friction several pairs at a time, dpd-core's
    /// `ou_updates`, bitwise its `ou_update`); then the velocity updates, one after the other.
    /// A chunk's passes stay in the cache, and the pairs' order is the sweep's: the same
    /// updates, bit for bit, as one pass of each over all pairs. Returns `DPD_LAMMPS_STYLE`,
    /// changing nothing, when [`Kernels::style`] refuses `conservative`.
    fn sweep_pairs(
        &self,
        sweep: Sweep,
        pairs: &[[c_int; 2]],
        atoms: &Atoms,
        v: &mut [f64],
        conservative: Option<&Conservative>,
        mut virial: Option<&mut [f64; 6]>,
    ) -> c_int {
        let conservative = match self.style(sweep.flow, conservative) {
            Ok(Some(style)) => style,
            Ok(None) => return DPD_LAMMPS_OK,
            Err(status) => return status,
        };
        let mut scratch = Scratch::default();
        scratch.near.reserve(CHUNK);
        let mut chunk = |pairs: &[[c_int; 2]]| {
            self.near_pairs(atoms, pairs, &mut scratch.near);
            let virial = virial.as_deref_mut();
            self.apply(sweep, atoms, v, conservative, virial, &mut scratch);
        };
        if sweep.reverse {
            pairs.chunks(CHUNK).rev().for_each(&mut chunk);
        } else {
            pairs.chunks(CHUNK).for_each(&mut chunk);
        }
        DPD_LAMMPS_OK
    }

    /// The pairs of `pairs` within their cutoff, with their geometry, into `near`.
    fn near_pairs(&self, atoms: &Atoms, pairs: &[[c_int; 2]], near: &mut Vec<Near>) {
        near.clear();
        for &[i, j] in pairs {
            let (i, j) = (i as usize, j as usize);
            let slot = self.slot(atoms, i, j);
            if let Some((e, r, w)) = Self::geometry(atoms, i, j, self.pairs[slot].rc) {
                near.push(Near {
                    i,
                    j,
                    e,
                    r,
                    w,
                    slot,
                });
            }
        }
    }

    /// The conservative style a sweep of `flow` includes (`Some(None)` for O and Ob, which
    /// include none), `None` when the sweep changes nothing (O and Ob without friction), or
    /// `DPD_LAMMPS_STYLE` for T without a style covering the kernels' types.
    #[allow(clippy::type_complexity)]
    fn style<'c>(
        &self,
        flow: SweepFlow,
        conservative: Option<&'c Conservative<'c>>,
    ) -> Result<Option<Option<&'c Conservative<'c>>>, c_int> {
        match (flow, conservative) {
            // The atoms' types are bounded by `ntypes`; the style must cover them.
            (SweepFlow::Trotter, Some(c)) if c.ntypes() >= self.ntypes => Ok(Some(Some(c))),
            (SweepFlow::Trotter, _) => Err(DPD_LAMMPS_STYLE),
            _ if !self.friction => Ok(None),
            _ => Ok(Some(None)),
        }
    }

    /// The last three passes of a sweep over the pairs `scratch.near` within their cutoff
    /// (see [`Kernels::sweep_pairs`]).
    fn apply(
        &self,
        sweep: Sweep,
        atoms: &Atoms,
        v: &mut [f64],
        conservative: Option<&Conservative>,
        mut virial: Option<&mut [f64; 6]>,
        scratch: &mut Scratch,
    ) {
        let Sweep {
            flow,
            h,
            key: (seed, step, stream),
            reverse,
        } = sweep;
        let Scratch { near, z, changes } = scratch;
        z.clear();
        z.resize(near.len(), 0.0);
        let tags = |p: &Near| (atoms.tag.key(p.i), atoms.tag.key(p.j));
        dpd_core::rng::pair_normals(seed, step, stream, |k| tags(&near[k]), z);
        let inv_mass = atoms.inv_mass;
        let mu = |p: &Near| inv_mass[p.i] + inv_mass[p.j];
        changes.clear();
        match (flow, self.uniform_gamma) {
            (SweepFlow::Ou, Some(gamma)) => ou_updates(
                (gamma, self.kbt, h),
                |k| self.weights.w_r(near[k].w),
                |k| mu(&near[k]),
                z,
                changes,
            ),
            _ => changes.extend(near.iter().zip(z.iter()).map(|(p, &z)| {
                let f = conservative.map_or(0.0, |s| {
                    let (ti, tj) = (atoms.type_of(p.i), atoms.type_of(p.j));
                    s.pair_force_of_types(ti, tj, p.r)
                });
                self.change(flow, h, p, mu(p), z, f)
            })),
        }
        // The velocities as one `[f64; 3]` per atom: one bounds check per atom and pair.
        let n = v.len() / 3;
        // SAFETY: `[f64; 3]` has the layout of three consecutive `f64`; the first `3 n` values
        // of `v`, borrowed mutably here and not used otherwise while `v3` lives.
        let v3 = unsafe { std::slice::from_raw_parts_mut(v.as_mut_ptr().cast::<[f64; 3]>(), n) };
        let mut apply = |(p, change): (&Near, &Change)| {
            let (i, j, e) = (p.i, p.j, p.e);
            let (mi, mj) = (inv_mass[i], inv_mass[j]);
            let (vi, vj) = (v3[i], v3[j]);
            let u = (0..3).map(|k| e[k] * (vi[k] - vj[k])).sum::<f64>();
            let impulse = change.slope * u + change.offset;
            for k in 0..3 {
                v3[i][k] += impulse * e[k] * mi;
                v3[j][k] -= impulse * e[k] * mj;
            }
            if let Some(virial) = virial.as_deref_mut() {
                add_virial(virial, atoms, i, j, impulse - change.conservative, e);
            }
        };
        if reverse {
            near.iter().zip(changes.iter()).rev().for_each(&mut apply);
        } else {
            near.iter().zip(changes.iter()).for_each(&mut apply);
        }
    }

    /// Add the dissipative and random pair forces of the full DPD force (the F letter, without
    /// its conservative part, which the engine computes) at velocities `v` to `f` (`3 n`
    /// doubles): `(-gamma_IJ w_R^2 u + sigma_IJ w_R z / sqrt(dt)) e_ij` on i, the opposite on
    /// j, with the normals of `key`. With `virial`, adds each pair's `r_ij (x) F_ij` to it
    /// ([`add_virial`]). Returns a `DPD_LAMMPS_*` status; on an error `f` is unchanged.
    #[allow(clippy::too_many_arguments)]
    pub fn dissipative_random(
        &self,
        dt: f64,
        (seed, step, stream): (u64, u64, u8),
        pairs: &[[c_int; 2]],
        atoms: &Atoms,
        v: &[f64],
        f: &mut [f64],
        mut virial: Option<&mut [f64; 6]>,
    ) -> c_int {
        let status = atoms.check(pairs, v.len(), self.ntypes);
        if status != DPD_LAMMPS_OK {
            return status;
        }
        if f.len() < 3 * atoms.len() {
            return DPD_LAMMPS_INDEX;
        }
        let root_dt = dt.sqrt();
        for &[i, j] in pairs {
            let (i, j) = (i as usize, j as usize);
            let c = self.coefficients(atoms, i, j);
            let Some((e, _, w)) = Self::geometry(atoms, i, j, c.rc) else {
                continue;
            };
            let noise = c.sigma / root_dt;
            let z = if noise > 0.0 {
                pair_normal(seed, step, stream, atoms.tag.key(i), atoms.tag.key(j))
            } else {
                0.0
            };
            let u = (0..3)
                .map(|k| e[k] * (v[3 * i + k] - v[3 * j + k]))
                .sum::<f64>();
            let force = full_pair_force(0.0, c.gamma, noise, self.weights.w_r(w), u, z);
            for k in 0..3 {
                f[3 * i + k] += force * e[k];
                f[3 * j + k] -= force * e[k];
            }
            if let Some(virial) = virial.as_deref_mut() {
                add_virial(virial, atoms, i, j, force, e);
            }
        }
        DPD_LAMMPS_OK
    }
}

/// Add the virial of the pair force (or impulse) `magnitude e` on atom i, `-magnitude e` on
/// atom j, to `virial`: `r_ij (x) magnitude e` with `r_ij = x_i - x_j`, in LAMMPS's order
/// xx, yy, zz, xy, xz, yz.
fn add_virial(
    virial: &mut [f64; 6],
    atoms: &Atoms,
    i: usize,
    j: usize,
    magnitude: f64,
    e: [f64; 3],
) {
    let (r, _) = atoms.separation(i, j);
    for (slot, (a, b)) in [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)]
        .into_iter()
        .enumerate()
    {
        virial[slot] += r[a] * magnitude * e[b];
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::abi::dpd_lammps_sweep;
    use std::ffi::c_void;

    /// Two atoms of different masses approaching each other, a third out of range; types 1,
    /// 1, 1 (or as given).
    struct Scene {
        x: Vec<f64>,
        v: Vec<f64>,
        inv_mass: Vec<f64>,
        tag: Vec<i32>,
        types: Vec<c_int>,
    }

    fn scene() -> Scene {
        Scene {
            x: vec![0.0, 0.0, 0.0, 0.6, 0.2, -0.1, 5.0, 5.0, 5.0],
            v: vec![0.5, -0.2, 0.1, -0.7, 0.3, 0.4, 1.0, 1.0, 1.0],
            inv_mass: vec![1.0, 0.5, 1.0],
            tag: vec![7, 3, 11],
            types: vec![1, 1, 1],
        }
    }

    /// `n` atoms in a cube of side 2 with velocities in [-0.5, 0.5) from a linear congruential
    /// stream seeded by `seed`, masses 1, 2, 3 in turn, tags `tag(k)`, types 1 and 2 in turn.
    fn random_scene(n: usize, seed: u64, tag: impl Fn(i32) -> i32) -> Scene {
        let mut state = seed;
        let mut next = move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let x = (0..3 * n).map(|_| 2.0 * next()).collect();
        Scene {
            x,
            v: (0..3 * n).map(|_| next() - 0.5).collect(),
            inv_mass: (0..n).map(|k| 1.0 / (1.0 + (k % 3) as f64)).collect(),
            tag: (0..n as i32).map(tag).collect(),
            types: (0..n).map(|k| 1 + (k % 2) as c_int).collect(),
        }
    }

    impl Scene {
        fn atoms(&self) -> Atoms<'_> {
            Atoms {
                x: &self.x,
                inv_mass: &self.inv_mass,
                tag: Tags::Small(&self.tag),
                types: &self.types,
            }
        }
    }

    fn momentum(v: &[f64], inv_mass: &[f64]) -> [f64; 3] {
        let mut p = [0.0; 3];
        for (k, m) in inv_mass.iter().enumerate() {
            for c in 0..3 {
                p[c] += v[3 * k + c] / m;
            }
        }
        p
    }

    /// The separation `x_0 - x_1` of the scene, its length and direction.
    fn pair01() -> ([f64; 3], f64, [f64; 3]) {
        let d: [f64; 3] = [-0.6, -0.2, 0.1];
        let r = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        (d, r, d.map(|c| c / r))
    }

    /// The O update of one pair against its formula from algorithms.md section 2, evaluated
    /// here independently: `u' = u e^{-tau h} + sqrt(kT mu (1 - e^{-2 tau h})) z` along `e` with
    /// `tau = gamma w^2 mu` (s = 2), momentum unchanged, the far atom untouched.
    #[test]
    fn one_pair_gets_the_exact_ou_update_and_momentum_is_kept() {
        let (gamma, kbt, rc, h) = (4.5, 1.3, 1.0, 0.05);
        let k = Kernels::uniform(gamma, kbt, rc, 2.0).unwrap();
        let mut s = scene();
        let before = s.v.clone();
        let mut v = s.v.clone();
        let mut virial = [0.0; 6];
        let status = k.sweep(
            Sweep {
                flow: SweepFlow::Ou,
                h,
                key: (42, 9, 2),
                reverse: false,
            },
            &[[0, 1], [0, 2]],
            &s.atoms(),
            &mut v,
            None,
            Some(&mut virial),
        );
        assert_eq!(status, DPD_LAMMPS_OK);
        s.v = v;
        let (d, r, e) = pair01();
        let mu = 1.0 + 0.5;
        let tau = gamma * (1.0 - r / rc).powi(2) * mu;
        let u = |v: &[f64]| (0..3).map(|c| e[c] * (v[c] - v[3 + c])).sum::<f64>();
        let z = pair_normal(42, 9, 2, 3, 7);
        let expected =
            u(&before) * (-tau * h).exp() + (kbt * mu * (1.0 - (-2.0 * tau * h).exp())).sqrt() * z;
        assert!(
            (u(&s.v) - expected).abs() < 1e-12,
            "{} vs {expected}",
            u(&s.v)
        );
        // The impulse on atom 0 is its momentum change; the virial is d (x) impulse.
        let impulse: [f64; 3] = std::array::from_fn(|c| s.v[c] - before[c]);
        for (slot, (a, b)) in [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)]
            .into_iter()
            .enumerate()
        {
            assert!(
                (virial[slot] - d[a] * impulse[b]).abs() < 1e-12,
                "{virial:?}"
            );
        }
        let (p0, p1) = (momentum(&before, &s.inv_mass), momentum(&s.v, &s.inv_mass));
        for c in 0..3 {
            assert!((p0[c] - p1[c]).abs() < 1e-14);
        }
        assert_eq!(&s.v[6..], &before[6..]);
    }

    /// Per type pair: a pair of types 1 and 2 gets the O update with gamma_12 and the weight
    /// of r_c,12, as `pair dpd`'s coefficients of that type pair mean; with r_c,12 below the
    /// pair's distance it is left alone, whatever the other pairs' cutoffs.
    #[test]
    fn a_pair_of_two_types_uses_the_friction_and_cutoff_of_its_type_pair() {
        let (kbt, h) = (1.0, 0.1);
        // gamma_11 = 1, gamma_12 = 20 (r_c 0.9), gamma_22 = 3.
        let gamma = [0.0, 0.0, 0.0, 0.0, 1.0, 20.0, 0.0, 20.0, 3.0];
        let mut s = scene();
        s.types = vec![1, 2, 2];
        let before = s.v.clone();
        let (_, r, e) = pair01();
        let u = |v: &[f64]| (0..3).map(|c| e[c] * (v[c] - v[3 + c])).sum::<f64>();
        for (rc12, moves) in [(0.9, true), (0.6, false)] {
            let rc = [0.0, 0.0, 0.0, 0.0, 1.0, rc12, 0.0, rc12, 1.0];
            let k = Kernels::new(kbt, 2.0, 2, &gamma, &rc).unwrap();
            let mut v = before.clone();
            let status = k.sweep(
                Sweep {
                    flow: SweepFlow::Ou,
                    h,
                    key: (1, 2, 0),
                    reverse: false,
                },
                &[[0, 1]],
                &s.atoms(),
                &mut v,
                None,
                None,
            );
            assert_eq!(status, DPD_LAMMPS_OK);
            if moves {
                let mu = 1.5;
                let x = 20.0 * (1.0 - r / rc12).powi(2) * mu * h;
                let z = pair_normal(1, 2, 0, 3, 7);
                let expected =
                    u(&before) * (-x).exp() + (kbt * mu * (1.0 - (-2.0 * x).exp())).sqrt() * z;
                assert!((u(&v) - expected).abs() < 1e-12, "{} vs {expected}", u(&v));
            } else {
                assert_eq!(v, before);
            }
        }
    }

    #[test]
    fn asymmetric_and_invalid_coefficients_name_the_type_pair() {
        let rc = [1.0; 9];
        let asymmetric = [0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 0.0, 3.0, 1.0];
        let e = Kernels::new(1.0, 2.0, 2, &asymmetric, &rc).err().unwrap();
        assert!(
            e.contains("type pair 1 2") && e.contains("symmetric"),
            "{e}"
        );
        let negative = [0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 0.0, 2.0, -1.0];
        let e = Kernels::new(1.0, 2.0, 2, &negative, &rc).err().unwrap();
        assert!(e.contains("type pair 2 2") && e.contains("gamma"), "{e}");
    }

    /// F's dissipative and random pair force against `-gamma w^2 u + sigma w z / sqrt(dt)`
    /// (s = 2, sigma^2 = 2 gamma kT), equal and opposite on the two atoms, none beyond r_c.
    #[test]
    fn the_pair_force_of_f_is_the_dpd_force_without_its_conservative_part() {
        let (gamma, kbt, dt) = (4.5, 1.3, 0.04);
        let k = Kernels::uniform(gamma, kbt, 1.0, 2.0).unwrap();
        let s = scene();
        let mut f = vec![0.0; 9];
        let status = k.dissipative_random(
            dt,
            (5, 6, 1),
            &[[0, 1], [1, 2]],
            &s.atoms(),
            &s.v,
            &mut f,
            None,
        );
        assert_eq!(status, DPD_LAMMPS_OK);
        let (_, r, e) = pair01();
        let w = 1.0 - r;
        let u = (0..3).map(|c| e[c] * (s.v[c] - s.v[3 + c])).sum::<f64>();
        let sigma = (2.0 * gamma * kbt).sqrt();
        let z = pair_normal(5, 6, 1, 7, 3);
        let expected = -gamma * w * w * u + sigma * w * z / dt.sqrt();
        for c in 0..3 {
            assert!((f[c] - expected * e[c]).abs() < 1e-12, "{f:?}");
            assert_eq!(f[3 + c], -f[c]);
            assert_eq!(f[6 + c], 0.0);
        }
    }

    #[test]
    fn bad_indices_tags_and_types_are_refused_without_change() {
        let k = Kernels::uniform(4.5, 1.0, 1.0, 2.0).unwrap();
        let mut s = scene();
        let before = s.v.clone();
        let sweep = |s: &Scene, pairs: &[[c_int; 2]]| {
            let mut v = s.v.clone();
            let status = k.sweep(
                Sweep {
                    flow: SweepFlow::Bbk,
                    h: 0.1,
                    key: (1, 1, 0),
                    reverse: false,
                },
                pairs,
                &s.atoms(),
                &mut v,
                None,
                None,
            );
            assert_eq!(v == before, status != DPD_LAMMPS_OK || pairs.is_empty());
            status
        };
        assert_eq!(sweep(&s, &[[0, 3]]), DPD_LAMMPS_INDEX);
        assert_eq!(sweep(&s, &[[-1, 0]]), DPD_LAMMPS_INDEX);
        s.types[2] = 2;
        assert_eq!(sweep(&s, &[[0, 1]]), DPD_LAMMPS_TYPE);
        s.types[2] = 1;
        s.tag[1] = -4;
        assert_eq!(sweep(&s, &[[0, 1]]), DPD_LAMMPS_TAG);
    }

    /// The C entry points: a sweep through the ABI equals the Rust call, with 32-bit and with
    /// 64-bit tags; null arrays where values are needed, tag widths other than 4 or 8 and
    /// streams outside 0..=255 are refused with no velocity changed.
    #[test]
    fn the_c_abi_checks_its_pointers_and_sweeps_like_the_rust_call() {
        let k = Kernels::uniform(4.5, 1.0, 1.0, 2.0).unwrap();
        let s = scene();
        let pairs: [c_int; 4] = [0, 1, 1, 2];
        let mut expected = s.v.clone();
        let status = k.sweep(
            Sweep {
                flow: SweepFlow::Ou,
                h: 0.1,
                key: (3, 4, 5),
                reverse: false,
            },
            &[[0, 1], [1, 2]],
            &s.atoms(),
            &mut expected,
            None,
            None,
        );
        assert_eq!(status, DPD_LAMMPS_OK);
        let wide: Vec<i64> = s.tag.iter().map(|&t| i64::from(t)).collect();
        let call =
            |stream: c_int, v: *mut f64, x: *const f64, (tag, bytes): (*const c_void, c_int)| {
                // SAFETY: every non-null pointer points to arrays of the lengths given.
                unsafe {
                    dpd_lammps_sweep(
                        &k,
                        0,
                        0.1,
                        3,
                        4,
                        stream,
                        0,
                        2,
                        pairs.as_ptr(),
                        3,
                        x,
                        v,
                        s.inv_mass.as_ptr(),
                        tag,
                        bytes,
                        s.types.as_ptr(),
                        std::ptr::null(),
                        std::ptr::null(),
                        std::ptr::null_mut(),
                    )
                }
            };
        let small = (s.tag.as_ptr().cast::<c_void>(), 4);
        let big = (wide.as_ptr().cast::<c_void>(), 8);
        for tags in [small, big] {
            let mut through_abi = s.v.clone();
            assert_eq!(
                call(5, through_abi.as_mut_ptr(), s.x.as_ptr(), tags),
                DPD_LAMMPS_OK
            );
            assert_eq!(through_abi, expected);
        }
        let mut untouched = s.v.clone();
        let v = untouched.as_mut_ptr();
        assert_eq!(call(256, v, s.x.as_ptr(), small), DPD_LAMMPS_FLOW);
        assert_eq!(call(5, v, s.x.as_ptr(), (small.0, 2)), DPD_LAMMPS_TAG);
        assert_eq!(
            call(5, std::ptr::null_mut(), s.x.as_ptr(), small),
            DPD_LAMMPS_NULL
        );
        assert_eq!(call(5, v, std::ptr::null(), small), DPD_LAMMPS_NULL);
        assert_eq!(untouched, s.v);
    }

    /// The T update of one pair against its formula from algorithms.md section 2, evaluated
    /// here independently: `u' = u e^{-tau h} + (f mu / tau)(1 - e^{-tau h}) + sqrt(kT mu (1 -
    /// e^{-2 tau h})) z` with the `dpd/soft` force `f = a_12 (1 - r/r_c,12)` of the atoms'
    /// types; the virial holds the impulse less its conservative part `f h`. Without the
    /// style, or with a style of fewer types, the sweep is refused with nothing changed.
    #[test]
    fn one_pair_gets_the_exact_trotter_update_with_its_types_soft_force() {
        let (gamma, kbt, h) = (4.5, 1.3, 0.05);
        let k = Kernels::new(kbt, 2.0, 2, &[gamma; 9], &[1.0; 9]).unwrap();
        let mut s = scene();
        s.types = vec![1, 2, 2];
        let before = s.v.clone();
        // Two types: a_12 = 30 with cutoff 0.9 (so the pair's force uses its own cutoff).
        let a = [0.0, 0.0, 0.0, 0.0, 25.0, 30.0, 0.0, 30.0, 40.0];
        let rc = [0.0, 0.0, 0.0, 0.0, 1.0, 0.9, 0.0, 0.9, 1.0];
        let style = SoftStyle::new(2, &a, &rc, [1.0; 4]).unwrap();
        let one_type = SoftStyle::new(1, &a, &rc, [1.0; 4]).unwrap();
        let mut virial = [0.0; 6];
        let sweep = |v: &mut [f64], c: Option<&Conservative>, virial: Option<&mut [f64; 6]>| {
            let pairs = [[0, 1], [0, 2]];
            k.sweep(
                Sweep {
                    flow: SweepFlow::Trotter,
                    h,
                    key: (42, 9, 2),
                    reverse: false,
                },
                &pairs,
                &s.atoms(),
                v,
                c,
                virial,
            )
        };
        let mut v = before.clone();
        assert_eq!(sweep(&mut v, None, None), DPD_LAMMPS_STYLE);
        assert_eq!(sweep(&mut v, Some(&one_type), None), DPD_LAMMPS_STYLE);
        assert_eq!(v, before);
        assert_eq!(
            sweep(&mut v, Some(&style), Some(&mut virial)),
            DPD_LAMMPS_OK
        );
        let (d, r, e) = pair01();
        let mu = 1.0 + 0.5;
        let tau = gamma * (1.0 - r).powi(2) * mu;
        let f = 30.0 * (1.0 - r / 0.9);
        let u = |v: &[f64]| (0..3).map(|c| e[c] * (v[c] - v[3 + c])).sum::<f64>();
        let z = pair_normal(42, 9, 2, 3, 7);
        let decay = (-tau * h).exp();
        let expected = u(&before) * decay
            + f * mu / tau * (1.0 - decay)
            + (kbt * mu * (1.0 - (-2.0 * tau * h).exp())).sqrt() * z;
        assert!((u(&v) - expected).abs() < 1e-12, "{} vs {expected}", u(&v));
        let impulse: [f64; 3] = std::array::from_fn(|c| v[c] - before[c]);
        for (slot, (a, b)) in [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)]
            .into_iter()
            .enumerate()
        {
            let expected = d[a] * (impulse[b] - f * h * e[b]);
            assert!((virial[slot] - expected).abs() < 1e-12, "{virial:?}");
        }
        let (p0, p1) = (momentum(&before, &s.inv_mass), momentum(&v, &s.inv_mass));
        for c in 0..3 {
            assert!((p0[c] - p1[c]).abs() < 1e-14);
        }
        assert_eq!(&v[6..], &before[6..]);
    }

    /// The four-pass sweep against the plain loop it replaces (each pair in turn: geometry,
    /// `pair_normal`, change, update), bitwise, for every flow, both orders and two types with
    /// their own cutoff and their own friction or one friction (where O computes its updates
    /// several at a time), on 60 atoms in a cube of side 2 (every pair listed: 1770 pairs,
    /// seven chunks of the sweep).
    #[test]
    fn the_sweep_is_bitwise_the_pair_by_pair_loop() {
        for gamma in [
            [0.0, 0.0, 0.0, 0.0, 4.5, 9.0, 0.0, 9.0, 20.0],
            [0.0, 0.0, 0.0, 0.0, 4.5, 4.5, 0.0, 4.5, 4.5],
        ] {
            sweep_and_pair_by_pair_loop(&gamma);
        }
    }

    fn sweep_and_pair_by_pair_loop(gamma: &[f64]) {
        let n: usize = 60;
        let scene = random_scene(n, 12345, |k| 1000 - 7 * k);
        let (inv_mass, tag, types) = (&scene.inv_mass, &scene.tag, &scene.types);
        let v0 = scene.v.clone();
        let atoms = scene.atoms();
        let pairs: Vec<[c_int; 2]> = (0..n as c_int)
            .flat_map(|i| (i + 1..n as c_int).map(move |j| [i, j]))
            .collect();
        let rc = [0.0, 0.0, 0.0, 0.0, 1.0, 0.9, 0.0, 0.9, 1.1];
        let k = Kernels::new(1.0, 2.0, 2, gamma, &rc).unwrap();
        assert_eq!(k.uniform_gamma.is_some(), gamma[5] == gamma[4]);
        let a = [0.0, 0.0, 0.0, 0.0, 25.0, 40.0, 0.0, 40.0, 25.0];
        let style = SoftStyle::new(2, &a, &rc, [1.0; 4]).unwrap();
        for flow in [SweepFlow::Ou, SweepFlow::Bbk, SweepFlow::Trotter] {
            for reverse in [false, true] {
                let key = (3, 17, 2);
                let mut fast = v0.clone();
                let (mut vf, mut vs) = ([0.0; 6], [0.0; 6]);
                let style = (flow == SweepFlow::Trotter).then_some(&style);
                let status = k.sweep(
                    Sweep {
                        flow,
                        h: 0.07,
                        key,
                        reverse,
                    },
                    &pairs,
                    &atoms,
                    &mut fast,
                    style,
                    Some(&mut vf),
                );
                assert_eq!(status, DPD_LAMMPS_OK);
                let mut slow = v0.clone();
                let mut visit = |&[i, j]: &[c_int; 2]| {
                    let (i, j) = (i as usize, j as usize);
                    let c = k.coefficients(&atoms, i, j);
                    let Some((e, r, w)) = Kernels::geometry(&atoms, i, j, c.rc) else {
                        return;
                    };
                    let z = pair_normal(key.0, key.1, key.2, tag[i] as u32, tag[j] as u32);
                    let f = style.map_or(0.0, |s| {
                        s.pair_force_of_types(types[i] as usize, types[j] as usize, r)
                    });
                    let slot = k.slot(&atoms, i, j);
                    let near = Near {
                        i,
                        j,
                        e,
                        r,
                        w,
                        slot,
                    };
                    let ch = k.change(flow, 0.07, &near, inv_mass[i] + inv_mass[j], z, f);
                    let u = (0..3)
                        .map(|d| e[d] * (slow[3 * i + d] - slow[3 * j + d]))
                        .sum::<f64>();
                    let impulse = ch.slope * u + ch.offset;
                    for d in 0..3 {
                        slow[3 * i + d] += impulse * e[d] * inv_mass[i];
                        slow[3 * j + d] -= impulse * e[d] * inv_mass[j];
                    }
                    add_virial(&mut vs, &atoms, i, j, impulse - ch.conservative, e);
                };
                if reverse {
                    pairs.iter().rev().for_each(&mut visit);
                } else {
                    pairs.iter().for_each(&mut visit);
                }
                assert_eq!(fast, slow, "{flow:?} reverse {reverse}");
                assert_eq!(vf, vs, "{flow:?} reverse {reverse}");
                assert_ne!(fast, v0);
            }
        }
    }

    /// A sweep over the pairs a `dpd/soft` evaluation recorded equals, bit for bit, the sweep
    /// over the neighbour list's pairs of the same atoms, for every flow, both orders and two
    /// colours visited one after the other (60 atoms in a cube of side 2, every pair listed
    /// once, two types whose pair-style cutoffs reach beyond the sweep's r_c or equal it); a
    /// record of other atoms, with an atom uncoloured, or of kernels of other types, and a
    /// colour beyond 7, are refused with nothing changed.
    #[test]
    fn a_sweep_over_recorded_pairs_is_bitwise_the_sweep_over_the_list() {
        let n: usize = 60;
        let scene = random_scene(n, 777, |k| 5 + 3 * k);
        let (x, types) = (&scene.x, &scene.types);
        let v0 = scene.v.clone();
        let atoms = scene.atoms();
        let gamma = [0.0, 0.0, 0.0, 0.0, 4.5, 9.0, 0.0, 9.0, 20.0];
        let rc = [0.0, 0.0, 0.0, 0.0, 1.0, 0.9, 0.0, 0.9, 1.1];
        let k = Kernels::new(1.0, 2.0, 2, &gamma, &rc).unwrap();
        let a = [0.0, 0.0, 0.0, 0.0, 25.0, 40.0, 0.0, 40.0, 25.0];
        let soft_rc = [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 1.2];
        let style = SoftStyle::new(2, &a, &soft_rc, [1.0; 4]).unwrap();
        // The list: atom i's neighbours are the atoms after it, the atoms from the last down,
        // as a list need not be in index order; colours: even and odd atoms.
        let neighbours = |i: usize| (i as c_int + 1..n as c_int).collect::<Vec<_>>();
        let colours: [Vec<c_int>; 2] =
            [0, 1].map(|c| (0..n as c_int).rev().filter(|i| i % 2 == c).collect());
        let evaluate = |record: &mut PairRecord, colour: &[u8]| {
            record.colour_atoms(colour);
            record.clear(n);
            let mut f = vec![0.0; 3 * n];
            for i in (0..n).rev() {
                let status = style.atom(
                    i,
                    &neighbours(i),
                    x,
                    types,
                    &mut f,
                    &mut soft::Tally::default(),
                    Some(record),
                );
                assert_eq!(status, DPD_LAMMPS_OK);
            }
        };
        let parity: Vec<u8> = (0..n).map(|k| (k % 2) as u8).collect();
        let mut record = PairRecord::new(&k);
        evaluate(&mut record, &parity);
        for flow in [SweepFlow::Ou, SweepFlow::Bbk, SweepFlow::Trotter] {
            let conservative = (flow == SweepFlow::Trotter).then_some(&style);
            for reverse in [false, true] {
                let (mut listed, mut recorded) = (v0.clone(), v0.clone());
                let (mut vl, mut vr) = ([0.0; 6], [0.0; 6]);
                for (c, colour) in colours.iter().enumerate() {
                    let key = (9, 4, c as u8);
                    let pairs: Vec<[c_int; 2]> = colour
                        .iter()
                        .flat_map(|&i| neighbours(i as usize).into_iter().map(move |j| [i, j]))
                        .collect();
                    let a = k.sweep(
                        Sweep {
                            flow,
                            h: 0.05,
                            key,
                            reverse,
                        },
                        &pairs,
                        &atoms,
                        &mut listed,
                        conservative,
                        Some(&mut vl),
                    );
                    let b = k.sweep_recorded(
                        Sweep {
                            flow,
                            h: 0.05,
                            key,
                            reverse,
                        },
                        (c, &record),
                        &atoms,
                        &mut recorded,
                        conservative,
                        Some(&mut vr),
                    );
                    assert_eq!((a, b), (DPD_LAMMPS_OK, DPD_LAMMPS_OK));
                }
                assert_eq!(listed, recorded, "{flow:?} reverse {reverse}");
                assert_eq!(vl, vr, "{flow:?} reverse {reverse}");
                assert_ne!(listed, v0);
            }
        }
        let mut v = v0.clone();
        let sweep = |k: &Kernels, colour: usize, record: &PairRecord, v: &mut [f64]| {
            k.sweep_recorded(
                Sweep {
                    flow: SweepFlow::Ou,
                    h: 0.05,
                    key: (1, 1, 0),
                    reverse: false,
                },
                (colour, record),
                &atoms,
                v,
                None,
                None,
            )
        };
        assert_eq!(sweep(&k, 8, &record, &mut v), DPD_LAMMPS_INDEX);
        let mut other = PairRecord::new(&k);
        other.clear(n - 1);
        assert_eq!(sweep(&k, 0, &other, &mut v), DPD_LAMMPS_INDEX);
        let mut uncoloured = parity.clone();
        uncoloured[7] = 8;
        evaluate(&mut other, &uncoloured);
        assert_eq!(sweep(&k, 0, &other, &mut v), DPD_LAMMPS_INDEX);
        let three = Kernels::new(1.0, 2.0, 3, &[4.5; 16], &[1.0; 16]).unwrap();
        assert_eq!(sweep(&three, 0, &record, &mut v), DPD_LAMMPS_INDEX);
        assert_eq!(v, v0);
    }

    #[test]
    fn invalid_parameters_name_the_field() {
        let e = Kernels::uniform(4.5, -1.0, 1.0, 2.0).err().unwrap();
        assert!(e.contains("kbt") && e.contains("-1"), "{e}");
    }
}
