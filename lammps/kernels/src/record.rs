//! The pairs within the sweeps' cutoff that a `dpd/soft` force evaluation found, kept for the
//! pairwise sweeps that follow at the same positions (ABOBA's O follows the force evaluation
//! with no drift between; SAS's first T the previous step's evaluation), so that a sweep does
//! not pass over the neighbour list again.
//!
//! The fix gives the record the colour (octant, 0 to 7) of every atom at the neighbour-list
//! build ([`PairRecord::colour_atoms`]); the evaluation appends each pair `(i, j)` to the
//! bucket of its atom i's colour, in the neighbour list's order. A colour's bucket is then the
//! sequence of pairs a sweep over the list's pairs of that colour's atoms visits (its atoms in
//! the list's order, each atom's pairs in turn), and a sweep over it applies the same updates,
//! bit for bit. Only the indices are kept (8 bytes a pair): the sweep computes each pair's
//! geometry again from the same positions with the same operations, which costs less than
//! writing and reading it back once the buckets outgrow the cache (docs/lammps-scaling.md).

use crate::{Kernels, DPD_LAMMPS_NULL, DPD_LAMMPS_OK};
use std::ffi::c_int;

/// The colour of an atom that has none (a ghost, or an atom the fix did not colour).
const NO_COLOUR: u8 = u8::MAX;

/// The in-range pairs of one evaluation over `natoms` atoms (owned and ghosts), by colour of
/// atom i, for the sweeps of one set of [`Kernels`] (their types and cutoffs).
#[derive(Debug)]
pub struct PairRecord {
    ntypes: usize,
    /// The sweeps' cutoff per type-pair slot.
    rc: Vec<f64>,
    /// Per atom its colour, [`NO_COLOUR`] for none.
    colour: Vec<u8>,
    natoms: usize,
    /// Whether every atom i of the evaluation had a colour (else the buckets are not used).
    complete: bool,
    buckets: [Vec<[c_int; 2]>; 8],
}

/// Where the pairs of one atom i go: its colour's bucket, with the sweeps' cutoffs.
pub struct Bucket<'a> {
    rc: &'a [f64],
    pairs: &'a mut Vec<[c_int; 2]>,
}

impl Bucket<'_> {
    /// Add the pair `(i, j)` of type-pair slot `slot` at `r2 = |x_i - x_j|^2` if it lies within
    /// the sweeps' cutoff of the slot (for a slot beyond the kernels' types, nothing).
    #[inline(always)]
    pub fn push(&mut self, (i, j): (usize, usize), r2: f64, slot: usize) {
        let Some(&rc) = self.rc.get(slot) else {
            return;
        };
        if r2 < rc * rc {
            self.pairs.push([i as c_int, j as c_int]);
        }
    }
}

impl PairRecord {
    /// An empty record for the sweeps of `kernels`.
    pub fn new(kernels: &Kernels) -> PairRecord {
        PairRecord {
            ntypes: kernels.ntypes(),
            rc: kernels.cutoffs(),
            colour: Vec::new(),
            natoms: 0,
            complete: false,
            buckets: Default::default(),
        }
    }

    /// The number of atom types of its kernels.
    pub fn ntypes(&self) -> usize {
        self.ntypes
    }

    /// Set the colour of each atom `k` to `colour[k]` (0 to 7; any other value: none) for the
    /// evaluations that follow.
    pub fn colour_atoms(&mut self, colour: &[u8]) {
        self.colour.clear();
        self.colour
            .extend(colour.iter().map(|&c| if c < 8 { c } else { NO_COLOUR }));
    }

    /// Forget the previous evaluation: no pairs, for `natoms` atoms.
    pub fn clear(&mut self, natoms: usize) {
        self.natoms = natoms;
        self.complete = true;
        self.buckets.iter_mut().for_each(Vec::clear);
    }

    /// Start the pairs of atom i (each atom once per evaluation): the bucket of its colour, or
    /// `None` for an atom without a colour, which makes the record incomplete.
    pub fn begin(&mut self, i: usize) -> Option<Bucket<'_>> {
        let colour = self.colour.get(i).copied().unwrap_or(NO_COLOUR);
        match self.buckets.get_mut(usize::from(colour)) {
            Some(pairs) => Some(Bucket {
                rc: &self.rc,
                pairs,
            }),
            None => {
                self.complete = false;
                None
            }
        }
    }

    /// The recorded pairs of atoms of colour `colour`, in order (indices below `natoms`), or
    /// `None` if the record is not complete, not of these `natoms` atoms, of kernels of another
    /// number of types, or `colour` is not 0 to 7.
    pub fn bucket(&self, colour: usize, natoms: usize, ntypes: usize) -> Option<&[[c_int; 2]]> {
        let valid = self.complete && natoms == self.natoms && ntypes == self.ntypes;
        self.buckets
            .get(colour)
            .filter(|_| valid)
            .map(Vec::as_slice)
    }
}

/// A new, empty record for the sweeps of `kernels` (null if it is null), to be freed with
/// [`dpd_lammps_record_free`].
///
/// # Safety
/// `kernels` is null or comes from [`crate::abi::dpd_lammps_new`].
#[no_mangle]
pub unsafe extern "C" fn dpd_lammps_record_new(kernels: *const Kernels) -> *mut PairRecord {
    // SAFETY: the contract.
    match unsafe { kernels.as_ref() } {
        Some(kernels) => Box::into_raw(Box::new(PairRecord::new(kernels))),
        None => std::ptr::null_mut(),
    }
}

/// Give the record the colour (0 to 7, other values: none) of each of the `natoms` atoms in
/// `colour`, for the evaluations that follow. Returns `DPD_LAMMPS_OK`, or `DPD_LAMMPS_NULL`
/// for a null record or a null `colour` with `natoms > 0`.
///
/// # Safety
/// `record` is null or from [`dpd_lammps_record_new`]; `colour` points to `natoms` bytes.
#[no_mangle]
pub unsafe extern "C" fn dpd_lammps_record_colours(
    record: *mut PairRecord,
    natoms: usize,
    colour: *const u8,
) -> c_int {
    // SAFETY: the contract.
    match unsafe { (record.as_mut(), crate::abi::slice(colour, natoms)) } {
        (Some(record), Some(colour)) => {
            record.colour_atoms(colour);
            DPD_LAMMPS_OK
        }
        _ => DPD_LAMMPS_NULL,
    }
}

/// Free a record made by [`dpd_lammps_record_new`]; null is ignored.
///
/// # Safety
/// `record` is null or a pointer returned by [`dpd_lammps_record_new`] not freed before.
#[no_mangle]
pub unsafe extern "C" fn dpd_lammps_record_free(record: *mut PairRecord) {
    if !record.is_null() {
        // SAFETY: made by `Box::into_raw`, freed once (the contract).
        drop(unsafe { Box::from_raw(record) });
    }
}
