//! The pairs within the cutoff that a `dpd/soft` force evaluation found, with their geometry,
//! kept for the pairwise sweeps that follow at the same positions (ABOBA's O follows the force
//! evaluation with no drift between; SAS's first T the previous step's evaluation), so that a
//! sweep does not pass over the neighbour list and recompute every pair's distance again.
//!
//! The record is filled pair by pair in the neighbour list's order and indexed by atom i, so a
//! sweep that visits atoms in the order of the list (one colour of the staged sweep at a time)
//! and each atom's recorded pairs in turn visits the in-range pairs in the order of the list,
//! and applies the same updates, bit for bit, as a sweep over the list's pairs.

use std::ffi::c_int;

/// One pair within the pair style's cutoff: atoms i and j, `e_ij = (x_i - x_j) / r`, `r` and
/// `r^2`, computed as [`crate::Kernels`]' sweeps compute them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Recorded {
    pub i: u32,
    pub j: u32,
    pub e: [f64; 3],
    pub r: f64,
    pub r2: f64,
}

/// The in-range pairs of one evaluation over `natoms` atoms (owned and ghosts), grouped by
/// atom i: those of atom i are `pairs[range[i].0..range[i].1]`.
#[derive(Debug, Default)]
pub struct PairRecord {
    natoms: usize,
    range: Vec<(u32, u32)>,
    pairs: Vec<Recorded>,
}

impl PairRecord {
    /// Forget the previous evaluation: no pairs, for `natoms` atoms.
    pub fn clear(&mut self, natoms: usize) {
        self.natoms = natoms;
        self.range.clear();
        self.range.resize(natoms, (0, 0));
        self.pairs.clear();
    }

    /// Start the pairs of atom i (each atom once per evaluation).
    pub fn begin(&mut self, i: usize) {
        let start = self.pairs.len() as u32;
        self.range[i] = (start, start);
    }

    /// Add a pair of atom i, the one last begun, with separation `d = x_i - x_j`, `r2 = |d|^2`
    /// and `r = sqrt(r2)`.
    #[inline(always)]
    pub fn push(&mut self, i: usize, j: usize, d: [f64; 3], r: f64, r2: f64) {
        self.pairs.push(Recorded {
            i: i as u32,
            j: j as u32,
            e: d.map(|c| c / r),
            r,
            r2,
        });
        self.range[i].1 = self.pairs.len() as u32;
    }

    /// The recorded pairs of each of the atoms `atoms` (indices as LAMMPS's), in that order,
    /// or `None` if the record is not of these `natoms` atoms or an index lies outside them.
    pub fn pairs_of(&self, atoms: &[c_int], natoms: usize) -> Option<Vec<&[Recorded]>> {
        if natoms != self.natoms {
            return None;
        }
        atoms
            .iter()
            .map(|&i| {
                let &(start, end) = self.range.get(usize::try_from(i).ok()?)?;
                Some(&self.pairs[start as usize..end as usize])
            })
            .collect()
    }
}

/// A new, empty record, to be freed with [`dpd_lammps_record_free`].
#[no_mangle]
pub extern "C" fn dpd_lammps_record_new() -> *mut PairRecord {
    Box::into_raw(Box::default())
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
