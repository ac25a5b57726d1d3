//! The C entry points of the kernels (`dpd_lammps.h` in the plugin): raw pointers in, checked
//! slices handed to [`Kernels`], a `DPD_LAMMPS_*` status out.

use crate::record::PairRecord;
use crate::soft::SoftStyle;
use crate::{
    Atoms, Conservative, Kernels, Sweep, SweepFlow, Tags, DPD_LAMMPS_FLOW, DPD_LAMMPS_INDEX,
    DPD_LAMMPS_NULL, DPD_LAMMPS_TAG,
};
use std::ffi::{c_char, c_int, c_void};

/// Create the kernels of one fix: `k_B T`, the weight exponent, and for `ntypes` atom types
/// the per type-pair friction `gamma` and cutoff `rc`, `(ntypes + 1)^2` doubles each at
/// `I * (ntypes + 1) + J` (row and column 0 unused). On invalid parameters returns null and
/// writes the message (naming the type pair, the field, its value and what is allowed),
/// truncated and NUL-terminated, into `message` when it is not null.
///
/// # Safety
/// `gamma` and `rc` are null or point to `(ntypes + 1)^2` doubles; `message` is null or
/// points to `message_len` writable bytes.
#[no_mangle]
pub unsafe extern "C" fn dpd_lammps_new(
    kbt: f64,
    exponent: f64,
    ntypes: c_int,
    gamma: *const f64,
    rc: *const f64,
    message: *mut c_char,
    message_len: usize,
) -> *mut Kernels {
    let made = match usize::try_from(ntypes) {
        Ok(ntypes) => {
            let table = (ntypes + 1) * (ntypes + 1);
            // SAFETY: the contract gives both tables their length.
            match unsafe { (slice(gamma, table), slice(rc, table)) } {
                (Some(gamma), Some(rc)) => Kernels::new(kbt, exponent, ntypes, gamma, rc),
                _ => Err("null gamma or r_c table".to_string()),
            }
        }
        Err(_) => Err(format!("ntypes = {ntypes} must be at least 1")),
    };
    match made {
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

/// `len` values at `p` as a slice; `None` if `p` is null while `len > 0`.
///
/// # Safety
/// A non-null `p` points to `len` valid values, not written during the call that made the
/// slice, and the slice is not used beyond that call.
pub(crate) unsafe fn slice<'a, T>(p: *const T, len: usize) -> Option<&'a [T]> {
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
pub(crate) unsafe fn slice_mut<'a, T>(p: *mut T, len: usize) -> Option<&'a mut [T]> {
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

/// The read-only arguments shared by the calls: the kernels, the noise key, the pair list and
/// the atoms.
struct Call<'a> {
    kernels: &'a Kernels,
    key: (u64, u64, u8),
    pairs: &'a [[c_int; 2]],
    atoms: Atoms<'a>,
}

impl<'a> Call<'a> {
    /// The shared arguments of a call, or the status of what is wrong: `DPD_LAMMPS_FLOW` for a
    /// stream outside 0..=255, `DPD_LAMMPS_TAG` for a tag width other than 4 or 8 bytes,
    /// `DPD_LAMMPS_NULL` for a null pointer where values are needed.
    ///
    /// # Safety
    /// `kernels` is null or comes from [`dpd_lammps_new`]; `pairs` points to `2 npairs` ints,
    /// `x` to `3 natoms` doubles, `inv_mass` to `natoms` doubles, `tag` to `natoms` integers
    /// of `tag_bytes` bytes each and `types` to `natoms` ints (each may be null when its
    /// length is 0), none written during the call.
    #[allow(clippy::too_many_arguments)]
    unsafe fn new(
        kernels: *const Kernels,
        (seed, step, stream): (u64, u64, c_int),
        (npairs, pairs): (usize, *const c_int),
        natoms: usize,
        (x, inv_mass): (*const f64, *const f64),
        (tag, tag_bytes): (*const c_void, c_int),
        types: *const c_int,
    ) -> Result<Call<'a>, c_int> {
        let stream = u8::try_from(stream).map_err(|_| DPD_LAMMPS_FLOW)?;
        // SAFETY: the caller's contract; `[c_int; 2]` has the layout of two consecutive ints.
        let tag = unsafe {
            match tag_bytes {
                4 => slice(tag.cast::<i32>(), natoms).map(Tags::Small),
                8 => slice(tag.cast::<i64>(), natoms).map(Tags::Big),
                _ => return Err(DPD_LAMMPS_TAG),
            }
        };
        // SAFETY: as above.
        let (kernels, pairs, x, inv_mass, types) = unsafe {
            (
                kernels.as_ref(),
                slice(pairs.cast::<[c_int; 2]>(), npairs),
                slice(x, 3 * natoms),
                slice(inv_mass, natoms),
                slice(types, natoms),
            )
        };
        match (kernels, pairs, x, inv_mass, tag, types) {
            (Some(kernels), Some(pairs), Some(x), Some(inv_mass), Some(tag), Some(types)) => {
                Ok(Call {
                    kernels,
                    key: (seed, step, stream),
                    pairs,
                    atoms: Atoms {
                        x,
                        inv_mass,
                        tag,
                        types,
                    },
                })
            }
            _ => Err(DPD_LAMMPS_NULL),
        }
    }
}

/// Apply the pairwise sweep `flow` (a [`SweepFlow`] code: 0 = O, 1 = Ob, 2 = T) of step length
/// `h` to `npairs` pairs (`pairs[2k]`, `pairs[2k + 1]` are the atom indices of pair k), in
/// order, or last to first when `reverse` is non-zero, with the noise of `(seed, step, stream)`.
/// The atoms: positions `x` and velocities `v` (`3 natoms` doubles), inverse masses, tags
/// (`tag_bytes` = 4 or 8 bytes each, LAMMPS's `sizeof(tagint)`) and types. T adds the
/// `dpd/soft` force with coefficients `soft_a` and cutoffs `soft_rc` (`(ntypes + 1)^2` doubles
/// each, `ntypes` that of the kernels, as in [`crate::soft`]); O and Ob ignore them (null is
/// allowed). `virial` is null, or 6 doubles to which each pair's `r_ij (x) J_ij` is added (xx,
/// yy, zz, xy, xz, yz; `J_ij` the impulse on atom i less its conservative part). Returns
/// `DPD_LAMMPS_OK`, or an error status with no velocity changed.
///
/// # Safety
/// `kernels` is null or comes from [`dpd_lammps_new`]; `pairs` points to `2 npairs` ints (may
/// be null when `npairs == 0`); `x` and `v` to `3 natoms` doubles, `v` writable; `inv_mass`
/// to `natoms` doubles, `tag` to `natoms` integers of `tag_bytes` bytes and `types` to
/// `natoms` ints; for T, `soft_a` and `soft_rc` as said above; `virial` is null or points to 6
/// writable doubles; the writable arrays overlap no other. Indices, tags and types are
/// checked against `natoms` and the kernels' `ntypes`, not trusted.
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
    tag: *const c_void,
    tag_bytes: c_int,
    types: *const c_int,
    soft_a: *const f64,
    soft_rc: *const f64,
    virial: *mut f64,
) -> c_int {
    // SAFETY: the contract.
    unsafe {
        with_sweep(
            (kernels, flow, seed, step, stream),
            (npairs, pairs),
            natoms,
            (x, v, inv_mass),
            (tag, tag_bytes, types),
            (soft_a, soft_rc, virial),
            |c, flow, v, style, virial| {
                c.kernels.sweep(
                    Sweep {
                        flow,
                        h,
                        key: c.key,
                        reverse: reverse != 0,
                    },
                    c.pairs,
                    &c.atoms,
                    v,
                    style,
                    virial,
                )
            },
        )
    }
}

/// [`dpd_lammps_sweep`] over the pairs that `record` holds of the atoms of colour `colour` (0
/// to 7), in place of a pair list ([`Kernels::sweep_recorded`]): `record` must come from a
/// `dpd/soft` evaluation ([`crate::soft::dpd_lammps_soft_forces`]) at the current positions of
/// these `natoms` atoms, with their colours. Returns `DPD_LAMMPS_INDEX` if it is not complete,
/// not of `natoms` atoms or of these kernels' number of types, or `colour` is not 0 to 7, else
/// as [`dpd_lammps_sweep`].
///
/// # Safety
/// As for [`dpd_lammps_sweep`], without `pairs`, and with `record` null or from
/// `dpd_lammps_record_new`, not written during the call.
#[no_mangle]
pub unsafe extern "C" fn dpd_lammps_sweep_recorded(
    kernels: *const Kernels,
    flow: c_int,
    h: f64,
    seed: u64,
    step: u64,
    stream: c_int,
    reverse: c_int,
    colour: c_int,
    record: *const PairRecord,
    natoms: usize,
    x: *const f64,
    v: *mut f64,
    inv_mass: *const f64,
    tag: *const c_void,
    tag_bytes: c_int,
    types: *const c_int,
    soft_a: *const f64,
    soft_rc: *const f64,
    virial: *mut f64,
) -> c_int {
    // SAFETY: the contract.
    let Some(record) = (unsafe { record.as_ref() }) else {
        return DPD_LAMMPS_NULL;
    };
    let Ok(colour) = usize::try_from(colour) else {
        return DPD_LAMMPS_INDEX;
    };
    // SAFETY: the contract.
    unsafe {
        with_sweep(
            (kernels, flow, seed, step, stream),
            (0, std::ptr::null()),
            natoms,
            (x, v, inv_mass),
            (tag, tag_bytes, types),
            (soft_a, soft_rc, virial),
            |c, flow, v, style, virial| {
                c.kernels.sweep_recorded(
                    Sweep {
                        flow,
                        h,
                        key: c.key,
                        reverse: reverse != 0,
                    },
                    (colour, record),
                    &c.atoms,
                    v,
                    style,
                    virial,
                )
            },
        )
    }
}

/// The checked arguments of a sweep call handed to `run`: the call, the flow, the velocities,
/// T's conservative style (built from `soft_a` and `soft_rc`) and the virial; or the status of
/// what is wrong.
///
/// # Safety
/// As for [`dpd_lammps_sweep`].
#[allow(clippy::type_complexity)]
unsafe fn with_sweep(
    (kernels, flow, seed, step, stream): (*const Kernels, c_int, u64, u64, c_int),
    pairs: (usize, *const c_int),
    natoms: usize,
    (x, v, inv_mass): (*const f64, *mut f64, *const f64),
    (tag, tag_bytes, types): (*const c_void, c_int, *const c_int),
    (soft_a, soft_rc, virial): (*const f64, *const f64, *mut f64),
    run: impl FnOnce(
        &Call,
        SweepFlow,
        &mut [f64],
        Option<&Conservative>,
        Option<&mut [f64; 6]>,
    ) -> c_int,
) -> c_int {
    let flow = match flow {
        0 => SweepFlow::Ou,
        1 => SweepFlow::Bbk,
        2 => SweepFlow::Trotter,
        _ => return DPD_LAMMPS_FLOW,
    };
    // SAFETY: the contract.
    let (call, v, virial) = unsafe {
        (
            Call::new(
                kernels,
                (seed, step, stream),
                pairs,
                natoms,
                (x, inv_mass),
                (tag, tag_bytes),
                types,
            ),
            slice_mut(v, 3 * natoms),
            virial_of(virial),
        )
    };
    let (c, v) = match (call, v) {
        (Ok(c), Some(v)) => (c, v),
        (Err(status), _) => return status,
        (_, None) => return DPD_LAMMPS_NULL,
    };
    let conservative = if flow == SweepFlow::Trotter {
        let ntypes = c.kernels.ntypes();
        let table = (ntypes + 1) * (ntypes + 1);
        // SAFETY: the contract gives each table its length.
        match unsafe { (slice(soft_a, table), slice(soft_rc, table)) } {
            (Some(a), Some(rc)) => SoftStyle::new(ntypes, a, rc, [1.0; 4]),
            _ => return DPD_LAMMPS_NULL,
        }
    } else {
        None
    };
    run(&c, flow, v, conservative.as_ref(), virial)
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
    tag: *const c_void,
    tag_bytes: c_int,
    types: *const c_int,
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
                natoms,
                (x, inv_mass),
                (tag, tag_bytes),
                types,
            ),
            slice(v, 3 * natoms),
            slice_mut(f, 3 * natoms),
            virial_of(virial),
        )
    };
    match (call, v, f) {
        (Ok(c), Some(v), Some(f)) => c
            .kernels
            .dissipative_random(dt, c.key, c.pairs, &c.atoms, v, f, virial),
        (Err(status), _, _) => status,
        _ => DPD_LAMMPS_NULL,
    }
}
