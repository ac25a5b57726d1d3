//! The physics of the LAMMPS plugin `fix dpd/split` (see `docs/lammps.md`): a small C ABI over
//! dpd-core's pairwise sweeps, so that the plugin's C++ only moves data and the pair updates,
//! pair weights and pair noise are those of `dpd run`.
//!
//! The plugin hands a sweep a list of `(i, j)` pairs, indices into LAMMPS's per-atom arrays
//! (owned atoms and ghost copies), and the arrays as LAMMPS stores them: positions and
//! velocities as `3 * n` contiguous doubles (`atom->x[0]`, `atom->v[0]`), inverse masses and
//! tags (global atom ids) per atom. The pairs are applied one after the other in the given
//! order (or reversed), each to the current velocities of both atoms, as in dpd-core's sweeps
//! (algorithms.md section 2): `u = e_ij . (v_i - v_j)`, `impulse = slope u + offset`,
//! `v_i += impulse e_ij / m_i`, `v_j -= impulse e_ij / m_j`. Pairs at `r >= r_c` are skipped.
//! The T sweep includes the pair's conservative force, that of the plugin's pair style
//! `dpd/soft` ([`soft::SoftStyle`]), in its exact update.
//! The normal of a pair is dpd-core's Philox pair normal keyed by
//! `(seed, step, stream, min(tag), max(tag))`, so each pair gets the same numbers whatever the
//! decomposition of the box over ranks.
//!
//! Licensed MIT (not MIT OR Apache-2.0 like the rest of the workspace): it is linked into a
//! plugin of LAMMPS, which is GPLv2, and MIT is compatible with it.

pub mod soft;

use dpd_core::flow::{bbk_update, ou_update, trotter_update, Change};
use dpd_core::force::full_pair_force;
use dpd_core::rng::pair_normal;
use dpd_core::Params;
use soft::SoftStyle;
use std::ffi::{c_char, c_int};

/// The sweep parameters of one fix: `gamma`, `k_B T`, cutoff and weight exponent, validated
/// by dpd-core ([`Params`]).
pub struct Kernels {
    params: Params,
}

/// Which pairwise sweep [`dpd_lammps_sweep`] applies.
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

/// The conservative force a T sweep includes: the `dpd/soft` coefficients and the atoms' types
/// (`n` values, LAMMPS's `atom->type`).
pub struct Conservative<'a> {
    pub style: SoftStyle<'a>,
    pub types: &'a [c_int],
}

/// Status of a call: 0 for success, else what was wrong.
pub const DPD_LAMMPS_OK: c_int = 0;
/// A null pointer where an array or handle was required.
pub const DPD_LAMMPS_NULL: c_int = 1;
/// A pair index at or beyond the number of atoms given.
pub const DPD_LAMMPS_INDEX: c_int = 2;
/// A flow code that is not a [`SweepFlow`].
pub const DPD_LAMMPS_FLOW: c_int = 3;
/// A negative tag (global atom id).
pub const DPD_LAMMPS_TAG: c_int = 4;
/// A T sweep without the conservative style, or an atom type outside it.
pub const DPD_LAMMPS_STYLE: c_int = 5;

impl Kernels {
    /// Validated parameters, or dpd-core's message naming the bad field, its value and what
    /// is allowed.
    pub fn new(gamma: f64, kbt: f64, rc: f64, exponent: f64) -> Result<Kernels, String> {
        Params::builder()
            .gamma(gamma)
            .kbt(kbt)
            .rc(rc)
            .weight_exponent(exponent)
            .build()
            .map(|params| Kernels { params })
            .map_err(|e| e.to_string())
    }

    /// The update of a pair at weight `w = 1 - r/r_c` with inverse reduced mass `mu`,
    /// standard normal `z` and conservative pair force `f` (used by T only).
    fn change(&self, flow: SweepFlow, h: f64, w: f64, mu: f64, z: f64, f: f64) -> Change {
        let p = &self.params;
        let wr = p.w_r(w);
        match flow {
            SweepFlow::Ou => ou_update(p.gamma(), p.kbt(), h, wr, mu, z),
            SweepFlow::Bbk => bbk_update(p.gamma(), p.sigma(), h, h.max(0.0).sqrt(), wr, mu, z),
            SweepFlow::Trotter => trotter_update(p.gamma(), p.kbt(), h, f, wr, mu, z),
        }
    }

    /// `DPD_LAMMPS_OK` when every pair index is below `n = inv_mass.len()`, the arrays are
    /// long enough and the tags non-negative, else the status of what is wrong.
    fn check(pairs: &[[c_int; 2]], x: &[f64], v: &[f64], inv_mass: &[f64], tag: &[c_int]) -> c_int {
        let n = inv_mass.len();
        let bad_index = |k: c_int| usize::try_from(k).map_or(true, |k| k >= n);
        if pairs.iter().flatten().any(|&k| bad_index(k)) || x.len() < 3 * n || v.len() < 3 * n {
            DPD_LAMMPS_INDEX
        } else if tag.len() < n || tag.iter().any(|&t| t < 0) {
            DPD_LAMMPS_TAG
        } else {
            DPD_LAMMPS_OK
        }
    }

    /// The unit vector `e_ij`, distance `r` and weight `w = 1 - r/r_c` of the pair `(i, j)` of
    /// positions `x` when `0 < r < r_c`.
    fn geometry(&self, x: &[f64], i: usize, j: usize) -> Option<([f64; 3], f64, f64)> {
        let rc = self.params.rc();
        let d: [f64; 3] = std::array::from_fn(|k| x[3 * i + k] - x[3 * j + k]);
        let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if r2 >= rc * rc || r2 == 0.0 {
            return None;
        }
        let r = r2.sqrt();
        Some((d.map(|c| c / r), r, 1.0 - r / rc))
    }

    /// Apply the sweep `flow` of step length `h` to `pairs` in the given order (see the crate
    /// documentation); `x`, `v` hold `3 n` doubles, `inv_mass` and `tag` `n` values; T needs
    /// `conservative`, the others ignore it. With `virial`, adds each pair's `r_ij (x) J_ij` to
    /// it ([`add_virial`]), `J_ij` the impulse on atom i less its conservative part (the pair
    /// style's virial holds that). Returns a `DPD_LAMMPS_*` status; on an error no velocity
    /// has changed.
    #[allow(clippy::too_many_arguments)]
    pub fn sweep(
        &self,
        flow: SweepFlow,
        h: f64,
        (seed, step, stream): (u64, u64, u8),
        pairs: &[[c_int; 2]],
        reverse: bool,
        x: &[f64],
        v: &mut [f64],
        inv_mass: &[f64],
        tag: &[c_int],
        conservative: Option<&Conservative>,
        mut virial: Option<&mut [f64; 6]>,
    ) -> c_int {
        let status = Self::check(pairs, x, v, inv_mass, tag);
        if status != DPD_LAMMPS_OK {
            return status;
        }
        let conservative = match (flow, conservative) {
            (SweepFlow::Trotter, Some(c)) => {
                // `check` has bounded the indices by the atom count.
                if pairs
                    .iter()
                    .flatten()
                    .any(|&k| c.style.type_of(c.types, k as usize).is_none())
                {
                    return DPD_LAMMPS_STYLE;
                }
                Some(c)
            }
            (SweepFlow::Trotter, None) => return DPD_LAMMPS_STYLE,
            _ if self.params.gamma() == 0.0 => return DPD_LAMMPS_OK,
            _ => None,
        };
        let mut apply = |&[i, j]: &[c_int; 2]| {
            let (i, j) = (i as usize, j as usize);
            let Some((e, r, w)) = self.geometry(x, i, j) else {
                return;
            };
            let (mi, mj) = (inv_mass[i], inv_mass[j]);
            let z = pair_normal(seed, step, stream, tag[i] as u32, tag[j] as u32);
            // Every atom's type was checked above.
            let f =
                conservative.map_or(0.0, |c| c.style.pair_force(c.types, i, j, r).unwrap_or(0.0));
            let c = self.change(flow, h, w, mi + mj, z, f);
            let u = (0..3)
                .map(|k| e[k] * (v[3 * i + k] - v[3 * j + k]))
                .sum::<f64>();
            let impulse = c.slope * u + c.offset;
            for k in 0..3 {
                v[3 * i + k] += impulse * e[k] * mi;
                v[3 * j + k] -= impulse * e[k] * mj;
            }
            if let Some(virial) = virial.as_deref_mut() {
                add_virial(virial, x, i, j, impulse - c.conservative, e);
            }
        };
        if reverse {
            pairs.iter().rev().for_each(&mut apply);
        } else {
            pairs.iter().for_each(&mut apply);
        }
        DPD_LAMMPS_OK
    }

    /// Add the dissipative and random pair forces of the full DPD force (the F letter, without
    /// its conservative part, which the engine computes) at velocities `v` to `f` (`3 n`
    /// doubles): `(-gamma w_R^2 u + sigma w_R z / sqrt(dt)) e_ij` on i, the opposite on j,
    /// with the normals of `key`. With `virial`, adds each pair's `r_ij (x) F_ij` to it
    /// ([`add_virial`]). Returns a `DPD_LAMMPS_*` status; on an error `f` is unchanged.
    #[allow(clippy::too_many_arguments)]
    pub fn dissipative_random(
        &self,
        dt: f64,
        (seed, step, stream): (u64, u64, u8),
        pairs: &[[c_int; 2]],
        x: &[f64],
        v: &[f64],
        inv_mass: &[f64],
        tag: &[c_int],
        f: &mut [f64],
        mut virial: Option<&mut [f64; 6]>,
    ) -> c_int {
        let status = Self::check(pairs, x, v, inv_mass, tag);
        if status != DPD_LAMMPS_OK {
            return status;
        }
        if f.len() < 3 * inv_mass.len() {
            return DPD_LAMMPS_INDEX;
        }
        let p = &self.params;
        let noise = p.sigma() / dt.sqrt();
        for &[i, j] in pairs {
            let (i, j) = (i as usize, j as usize);
            let Some((e, _, w)) = self.geometry(x, i, j) else {
                continue;
            };
            let z = if noise > 0.0 {
                pair_normal(seed, step, stream, tag[i] as u32, tag[j] as u32)
            } else {
                0.0
            };
            let u = (0..3)
                .map(|k| e[k] * (v[3 * i + k] - v[3 * j + k]))
                .sum::<f64>();
            let force = full_pair_force(0.0, p.gamma(), noise, p.w_r(w), u, z);
            for k in 0..3 {
                f[3 * i + k] += force * e[k];
                f[3 * j + k] -= force * e[k];
            }
            if let Some(virial) = virial.as_deref_mut() {
                add_virial(virial, x, i, j, force, e);
            }
        }
        DPD_LAMMPS_OK
    }
}

/// Add the virial of the pair force (or impulse) `magnitude e` on atom i, `-magnitude e` on
/// atom j, to `virial`: `r_ij (x) magnitude e` with `r_ij = x_i - x_j`, in LAMMPS's order
/// xx, yy, zz, xy, xz, yz.
fn add_virial(virial: &mut [f64; 6], x: &[f64], i: usize, j: usize, magnitude: f64, e: [f64; 3]) {
    let r: [f64; 3] = std::array::from_fn(|k| x[3 * i + k] - x[3 * j + k]);
    for (slot, (a, b)) in [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)]
        .into_iter()
        .enumerate()
    {
        virial[slot] += r[a] * magnitude * e[b];
    }
}

/// Create the kernels of one fix from its parameters. On invalid parameters returns null and
/// writes dpd-core's message (naming the field, its value and what is allowed), truncated and
/// NUL-terminated, into `message` when it is not null.
///
/// # Safety
/// `message` is null or points to `message_len` writable bytes.
#[no_mangle]
pub unsafe extern "C" fn dpd_lammps_new(
    gamma: f64,
    kbt: f64,
    rc: f64,
    exponent: f64,
    message: *mut c_char,
    message_len: usize,
) -> *mut Kernels {
    match Kernels::new(gamma, kbt, rc, exponent) {
        Ok(k) => Box::into_raw(Box::new(k)),
        Err(text) => {
            if !message.is_null() && message_len > 0 {
                let n = text.len().min(message_len - 1);
                // SAFETY: `message` has `message_len > n` writable bytes (the contract).
                unsafe {
                    std::ptr::copy_nonoverlapping(text.as_ptr().cast(), message, n);
                    *message.add(n) = 0;
                }
            }
            std::ptr::null_mut()
        }
    }
}

/// Free kernels made by [`dpd_lammps_new`]; null is ignored.
///
/// # Safety
/// `kernels` is null or a pointer returned by [`dpd_lammps_new`] not freed before.
#[no_mangle]
pub unsafe extern "C" fn dpd_lammps_free(kernels: *mut Kernels) {
    if !kernels.is_null() {
        // SAFETY: made by `Box::into_raw` in `dpd_lammps_new`, freed once (the contract).
        drop(unsafe { Box::from_raw(kernels) });
    }
}

/// The read-only arguments shared by the calls: the kernels, the noise key, the pair list,
/// and per atom the positions (`3 natoms` doubles), inverse masses and tags.
struct Call<'a> {
    kernels: &'a Kernels,
    key: (u64, u64, u8),
    pairs: &'a [[c_int; 2]],
    x: &'a [f64],
    inv_mass: &'a [f64],
    tag: &'a [c_int],
}

/// `len` values at `p` as a slice; `None` if `p` is null while `len > 0`.
///
/// # Safety
/// A non-null `p` points to `len` valid values, not written during the call that made the
/// slice, and the slice is not used beyond that call.
unsafe fn slice<'a, T>(p: *const T, len: usize) -> Option<&'a [T]> {
    match (len, p.is_null()) {
        (0, _) => Some(&[]),
        (_, true) => None,
        // SAFETY: the caller's contract.
        (len, false) => Some(unsafe { std::slice::from_raw_parts(p, len) }),
    }
}

/// As [`slice`], writable.
///
/// # Safety
/// As for [`slice`], and no other slice of the call overlaps it.
unsafe fn slice_mut<'a, T>(p: *mut T, len: usize) -> Option<&'a mut [T]> {
    match (len, p.is_null()) {
        (0, _) => Some(&mut []),
        (_, true) => None,
        // SAFETY: the caller's contract.
        (len, false) => Some(unsafe { std::slice::from_raw_parts_mut(p, len) }),
    }
}

/// The optional virial accumulator of a call: null for none, else 6 writable doubles.
///
/// # Safety
/// A non-null `virial` points to 6 writable doubles overlapping no other array of the call.
unsafe fn virial_of<'a>(virial: *mut f64) -> Option<&'a mut [f64; 6]> {
    // SAFETY: the caller's contract.
    unsafe { virial.cast::<[f64; 6]>().as_mut() }
}

impl<'a> Call<'a> {
    /// The shared arguments of a call, or the status of what is wrong: `DPD_LAMMPS_FLOW` for a
    /// stream outside 0..=255, `DPD_LAMMPS_NULL` for a null pointer where values are needed.
    ///
    /// # Safety
    /// `kernels` is null or comes from [`dpd_lammps_new`]; `pairs` points to `2 npairs` ints,
    /// `x` to `3 natoms` doubles, `inv_mass` to `natoms` doubles and `tag` to `natoms` ints
    /// (each may be null when its length is 0), none written during the call.
    unsafe fn new(
        kernels: *const Kernels,
        (seed, step, stream): (u64, u64, c_int),
        (npairs, pairs): (usize, *const c_int),
        (natoms, x, inv_mass, tag): (usize, *const f64, *const f64, *const c_int),
    ) -> Result<Call<'a>, c_int> {
        let stream = u8::try_from(stream).map_err(|_| DPD_LAMMPS_FLOW)?;
        // SAFETY: the caller's contract; `[c_int; 2]` has the layout of two consecutive ints.
        let (kernels, pairs, x, inv_mass, tag) = unsafe {
            (
                kernels.as_ref(),
                slice(pairs.cast::<[c_int; 2]>(), npairs),
                slice(x, 3 * natoms),
                slice(inv_mass, natoms),
                slice(tag, natoms),
            )
        };
        match (kernels, pairs, x, inv_mass, tag) {
            (Some(kernels), Some(pairs), Some(x), Some(inv_mass), Some(tag)) => Ok(Call {
                kernels,
                key: (seed, step, stream),
                pairs,
                x,
                inv_mass,
                tag,
            }),
            _ => Err(DPD_LAMMPS_NULL),
        }
    }
}

/// Apply the pairwise sweep `flow` (a [`SweepFlow`] code: 0 = O, 1 = Ob, 2 = T) of step length
/// `h` to `npairs` pairs (`pairs[2k]`, `pairs[2k + 1]` are the atom indices of pair k), in
/// order, or last to first when `reverse` is non-zero, with the noise of `(seed, step, stream)`.
/// T adds the `dpd/soft` force of `ntypes` types with coefficients `a` and cutoffs `rc`
/// (`(ntypes + 1)^2` doubles each, as in [`soft`]) and atom types `type_` (`natoms` ints); O
/// and Ob ignore them (null is allowed). `virial` is null, or 6 doubles to which each pair's
/// `r_ij (x) J_ij` is added (xx, yy, zz, xy, xz, yz; `J_ij` the impulse on atom i less its
/// conservative part). Returns `DPD_LAMMPS_OK`, or an error status with no velocity changed.
///
/// # Safety
/// `kernels` is null or comes from [`dpd_lammps_new`]; `pairs` points to `2 npairs` ints (may
/// be null when `npairs == 0`); `x` and `v` to `3 natoms` doubles, `v` writable; `inv_mass` to
/// `natoms` doubles and `tag` to `natoms` ints; for T, `a`, `rc` and `type_` as said above;
/// `virial` is null or points to 6 writable doubles; the writable arrays overlap no other.
/// Indices, tags and types are checked against `natoms` and `ntypes`, not trusted.
#[no_mangle]
pub unsafe extern "C" fn dpd_lammps_sweep(
    kernels: *const Kernels,
    flow: c_int,
    h: f64,
    seed: u64,
    step: u64,
    stream: c_int,
    reverse: c_int,
    npairs: usize,
    pairs: *const c_int,
    natoms: usize,
    x: *const f64,
    v: *mut f64,
    inv_mass: *const f64,
    tag: *const c_int,
    ntypes: c_int,
    a: *const f64,
    rc: *const f64,
    type_: *const c_int,
    virial: *mut f64,
) -> c_int {
    let flow = match flow {
        0 => SweepFlow::Ou,
        1 => SweepFlow::Bbk,
        2 => SweepFlow::Trotter,
        _ => return DPD_LAMMPS_FLOW,
    };
    let conservative = match (flow, usize::try_from(ntypes)) {
        (SweepFlow::Trotter, Ok(ntypes)) => {
            let table = (ntypes + 1) * (ntypes + 1);
            // SAFETY: the contract gives each array its length.
            let arrays = unsafe { (slice(a, table), slice(rc, table), slice(type_, natoms)) };
            let (Some(a), Some(rc), Some(types)) = arrays else {
                return DPD_LAMMPS_NULL;
            };
            SoftStyle::new(ntypes, a, rc, [1.0; 4]).map(|style| Conservative { style, types })
        }
        _ => None,
    };
    // SAFETY: the contract.
    let (call, v, virial) = unsafe {
        (
            Call::new(
                kernels,
                (seed, step, stream),
                (npairs, pairs),
                (natoms, x, inv_mass, tag),
            ),
            slice_mut(v, 3 * natoms),
            virial_of(virial),
        )
    };
    match (call, v) {
        (Ok(c), Some(v)) => c.kernels.sweep(
            flow,
            h,
            c.key,
            c.pairs,
            reverse != 0,
            c.x,
            v,
            c.inv_mass,
            c.tag,
            conservative.as_ref(),
            virial,
        ),
        (Err(status), _) => status,
        (_, None) => DPD_LAMMPS_NULL,
    }
}

/// Add the dissipative and random pair forces of the F letter (step `dt`) at velocities `v`
/// to `f` (`3 natoms` doubles), over `npairs` pairs as in [`dpd_lammps_sweep`], with the
/// noise of `(seed, step, stream)` ([`Kernels::dissipative_random`]); `virial` as there, with
/// the pair forces in place of the impulses. Returns `DPD_LAMMPS_OK`, or an error status with
/// `f` unchanged.
///
/// # Safety
/// As for [`dpd_lammps_sweep`], with `v` read only and `f` pointing to `3 natoms` writable
/// doubles overlapping none of the other arrays.
#[no_mangle]
pub unsafe extern "C" fn dpd_lammps_dissipative_random(
    kernels: *const Kernels,
    dt: f64,
    seed: u64,
    step: u64,
    stream: c_int,
    npairs: usize,
    pairs: *const c_int,
    natoms: usize,
    x: *const f64,
    v: *const f64,
    inv_mass: *const f64,
    tag: *const c_int,
    f: *mut f64,
    virial: *mut f64,
) -> c_int {
    // SAFETY: the contract.
    let (call, v, f, virial) = unsafe {
        (
            Call::new(
                kernels,
                (seed, step, stream),
                (npairs, pairs),
                (natoms, x, inv_mass, tag),
            ),
            slice(v, 3 * natoms),
            slice_mut(f, 3 * natoms),
            virial_of(virial),
        )
    };
    match (call, v, f) {
        (Ok(c), Some(v), Some(f)) => c
            .kernels
            .dissipative_random(dt, c.key, c.pairs, c.x, v, c.inv_mass, c.tag, f, virial),
        (Err(status), _, _) => status,
        _ => DPD_LAMMPS_NULL,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two atoms of different masses approaching each other, a third out of range.
    fn scene() -> (Vec<f64>, Vec<f64>, Vec<f64>, Vec<c_int>) {
        let x = vec![0.0, 0.0, 0.0, 0.6, 0.2, -0.1, 5.0, 5.0, 5.0];
        let v = vec![0.5, -0.2, 0.1, -0.7, 0.3, 0.4, 1.0, 1.0, 1.0];
        (x, v, vec![1.0, 0.5, 1.0], vec![7, 3, 11])
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

    /// The O update of one pair against its formula from algorithms.md section 2, evaluated
    /// here independently: `u' = u e^{-tau h} + sqrt(kT mu (1 - e^{-2 tau h})) z` along `e` with
    /// `tau = gamma w^2 mu` (s = 2), momentum unchanged, the far atom untouched.
    #[test]
    fn one_pair_gets_the_exact_ou_update_and_momentum_is_kept() {
        let (gamma, kbt, rc, h) = (4.5, 1.3, 1.0, 0.05);
        let k = Kernels::new(gamma, kbt, rc, 2.0).unwrap();
        let (x, mut v, inv_mass, tag) = scene();
        let before = v.clone();
        let key = (42, 9, 2);
        let mut virial = [0.0; 6];
        let status = k.sweep(
            SweepFlow::Ou,
            h,
            key,
            &[[0, 1], [0, 2]],
            false,
            &x,
            &mut v,
            &inv_mass,
            &tag,
            None,
            Some(&mut virial),
        );
        assert_eq!(status, DPD_LAMMPS_OK);
        let d: [f64; 3] = [-0.6, -0.2, 0.1];
        let r = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        let e = d.map(|c| c / r);
        let mu = 1.0 + 0.5;
        let tau = gamma * (1.0 - r / rc).powi(2) * mu;
        let u = |v: &[f64]| (0..3).map(|c| e[c] * (v[c] - v[3 + c])).sum::<f64>();
        let z = pair_normal(42, 9, 2, 3, 7);
        let expected =
            u(&before) * (-tau * h).exp() + (kbt * mu * (1.0 - (-2.0 * tau * h).exp())).sqrt() * z;
        assert!((u(&v) - expected).abs() < 1e-12, "{} vs {expected}", u(&v));
        // The impulse on atom 0 is its momentum change; the virial is d (x) impulse.
        let impulse: [f64; 3] = std::array::from_fn(|c| v[c] - before[c]);
        for (slot, (a, b)) in [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)]
            .into_iter()
            .enumerate()
        {
            assert!(
                (virial[slot] - d[a] * impulse[b]).abs() < 1e-12,
                "{virial:?}"
            );
        }
        let (p0, p1) = (momentum(&before, &inv_mass), momentum(&v, &inv_mass));
        for c in 0..3 {
            assert!((p0[c] - p1[c]).abs() < 1e-14);
        }
        assert_eq!(&v[6..], &before[6..]);
    }

    /// F's dissipative and random pair force against `-gamma w^2 u + sigma w z / sqrt(dt)`
    /// (s = 2, sigma^2 = 2 gamma kT), equal and opposite on the two atoms, none beyond r_c.
    #[test]
    fn the_pair_force_of_f_is_the_dpd_force_without_its_conservative_part() {
        let (gamma, kbt, dt) = (4.5, 1.3, 0.04);
        let k = Kernels::new(gamma, kbt, 1.0, 2.0).unwrap();
        let (x, v, inv_mass, tag) = scene();
        let mut f = vec![0.0; 9];
        let status = k.dissipative_random(
            dt,
            (5, 6, 1),
            &[[0, 1], [1, 2]],
            &x,
            &v,
            &inv_mass,
            &tag,
            &mut f,
            None,
        );
        assert_eq!(status, DPD_LAMMPS_OK);
        let d: [f64; 3] = [-0.6, -0.2, 0.1];
        let r = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        let e = d.map(|c| c / r);
        let w = 1.0 - r;
        let u = (0..3).map(|c| e[c] * (v[c] - v[3 + c])).sum::<f64>();
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
    fn bad_indices_and_tags_are_refused_without_change() {
        let k = Kernels::new(4.5, 1.0, 1.0, 2.0).unwrap();
        let (x, mut v, inv_mass, mut tag) = scene();
        let before = v.clone();
        let sweep = |v: &mut [f64], tag: &[c_int], pairs: &[[c_int; 2]]| {
            k.sweep(
                SweepFlow::Bbk,
                0.1,
                (1, 1, 0),
                pairs,
                false,
                &x,
                v,
                &inv_mass,
                tag,
                None,
                None,
            )
        };
        assert_eq!(sweep(&mut v, &tag, &[[0, 3]]), DPD_LAMMPS_INDEX);
        assert_eq!(sweep(&mut v, &tag, &[[-1, 0]]), DPD_LAMMPS_INDEX);
        tag[1] = -4;
        assert_eq!(sweep(&mut v, &tag, &[[0, 1]]), DPD_LAMMPS_TAG);
        assert_eq!(v, before);
    }

    /// The C entry points: a sweep through the ABI equals the Rust call; null arrays where
    /// values are needed and streams outside 0..=255 are refused with no velocity changed.
    #[test]
    fn the_c_abi_checks_its_pointers_and_sweeps_like_the_rust_call() {
        let k = Kernels::new(4.5, 1.0, 1.0, 2.0).unwrap();
        let (x, v, inv_mass, tag) = scene();
        let pairs: [c_int; 4] = [0, 1, 1, 2];
        let mut expected = v.clone();
        let status = k.sweep(
            SweepFlow::Ou,
            0.1,
            (3, 4, 5),
            &[[0, 1], [1, 2]],
            false,
            &x,
            &mut expected,
            &inv_mass,
            &tag,
            None,
            None,
        );
        assert_eq!(status, DPD_LAMMPS_OK);
        let call = |stream: c_int, v: *mut f64, x: *const f64| {
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
                    inv_mass.as_ptr(),
                    tag.as_ptr(),
                    0,
                    std::ptr::null(),
                    std::ptr::null(),
                    std::ptr::null(),
                    std::ptr::null_mut(),
                )
            }
        };
        let mut through_abi = v.clone();
        assert_eq!(call(5, through_abi.as_mut_ptr(), x.as_ptr()), DPD_LAMMPS_OK);
        assert_eq!(through_abi, expected);
        let mut untouched = v.clone();
        assert_eq!(
            call(256, untouched.as_mut_ptr(), x.as_ptr()),
            DPD_LAMMPS_FLOW
        );
        assert_eq!(call(5, std::ptr::null_mut(), x.as_ptr()), DPD_LAMMPS_NULL);
        assert_eq!(
            call(5, untouched.as_mut_ptr(), std::ptr::null()),
            DPD_LAMMPS_NULL
        );
        assert_eq!(untouched, v);
    }

    /// The T update of one pair against its formula from algorithms.md section 2, evaluated
    /// here independently: `u' = u e^{-tau h} + (f mu / tau)(1 - e^{-tau h}) + sqrt(kT mu (1 -
    /// e^{-2 tau h})) z` with the `dpd/soft` force `f = a_12 (1 - r/r_c,12)` of the atoms'
    /// types; the virial holds the impulse less its conservative part `f h`. Without the
    /// style, or with a type outside it, the sweep is refused with nothing changed.
    #[test]
    fn one_pair_gets_the_exact_trotter_update_with_its_types_soft_force() {
        let (gamma, kbt, h) = (4.5, 1.3, 0.05);
        let k = Kernels::new(gamma, kbt, 1.0, 2.0).unwrap();
        let (x, mut v, inv_mass, tag) = scene();
        let before = v.clone();
        // Two types: a_12 = 30 with cutoff 0.9 (so the pair's force uses its own cutoff).
        let a = [0.0, 0.0, 0.0, 0.0, 25.0, 30.0, 0.0, 30.0, 40.0];
        let rc = [0.0, 0.0, 0.0, 0.0, 1.0, 0.9, 0.0, 0.9, 1.0];
        let types = [1, 2, 2];
        let conservative = Conservative {
            style: SoftStyle::new(2, &a, &rc, [1.0; 4]).unwrap(),
            types: &types,
        };
        let mut virial = [0.0; 6];
        let sweep = |v: &mut [f64], c: Option<&Conservative>, virial: Option<&mut [f64; 6]>| {
            let pairs = [[0, 1], [0, 2]];
            k.sweep(
                SweepFlow::Trotter,
                h,
                (42, 9, 2),
                &pairs,
                false,
                &x,
                v,
                &inv_mass,
                &tag,
                c,
                virial,
            )
        };
        assert_eq!(sweep(&mut v, None, None), DPD_LAMMPS_STYLE);
        let bad_types = [1, 3, 1];
        let outside = Conservative {
            style: SoftStyle::new(2, &a, &rc, [1.0; 4]).unwrap(),
            types: &bad_types,
        };
        assert_eq!(sweep(&mut v, Some(&outside), None), DPD_LAMMPS_STYLE);
        assert_eq!(v, before);
        assert_eq!(
            sweep(&mut v, Some(&conservative), Some(&mut virial)),
            DPD_LAMMPS_OK
        );
        let d: [f64; 3] = [-0.6, -0.2, 0.1];
        let r = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        let e = d.map(|c| c / r);
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
        let (p0, p1) = (momentum(&before, &inv_mass), momentum(&v, &inv_mass));
        for c in 0..3 {
            assert!((p0[c] - p1[c]).abs() < 1e-14);
        }
        assert_eq!(&v[6..], &before[6..]);
    }

    #[test]
    fn invalid_parameters_name_the_field() {
        let e = Kernels::new(4.5, -1.0, 1.0, 2.0).err().unwrap();
        assert!(e.contains("kbt") && e.contains("-1"), "{e}");
    }
}
