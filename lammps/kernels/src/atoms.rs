//! The per-atom arrays a call reads, as LAMMPS stores them, and the check that makes every
//! index, tag and type of a call safe to use.

use crate::{DPD_LAMMPS_INDEX, DPD_LAMMPS_OK, DPD_LAMMPS_TAG, DPD_LAMMPS_TYPE};
use std::ffi::c_int;

/// Global atom ids (LAMMPS's `tagint`): 32-bit in LAMMPS's default integer sizes, 64-bit with
/// `-DLAMMPS_BIGBIG`. The pair noise is keyed by 32-bit ids, so a tag must
/// lie in `0..=u32::MAX` whatever its width ([`Atoms::check`]).
#[derive(Clone, Copy, Debug)]
pub enum Tags<'a> {
    Small(&'a [i32]),
    Big(&'a [i64]),
}

impl Tags<'_> {
    fn len(&self) -> usize {
        match self {
            Tags::Small(t) => t.len(),
            Tags::Big(t) => t.len(),
        }
    }

    /// Whether every tag fits the 32-bit key of the pair noise (folded without branches, so
    /// that the compiler vectorises it: the check runs at every sweep call).
    fn in_range(&self) -> bool {
        match self {
            Tags::Small(t) => t.iter().fold(true, |ok, &k| ok & (k >= 0)),
            Tags::Big(t) => t
                .iter()
                .fold(true, |ok, &k| ok & (k >= 0) & (k <= i64::from(u32::MAX))),
        }
    }

    /// The tag of atom `k` as the noise key takes it; [`Atoms::check`] has bounded `k` and
    /// the value.
    #[inline(always)]
    pub fn key(&self, k: usize) -> u32 {
        match self {
            Tags::Small(t) => t[k] as u32,
            Tags::Big(t) => t[k] as u32,
        }
    }
}

/// The atoms of a call, owned and ghosts, `n = inv_mass.len()` of them: positions (`3 n`
/// doubles, `atom->x[0]`), inverse masses, tags and types (`1..=ntypes`).
#[derive(Clone, Copy, Debug)]
pub struct Atoms<'a> {
    pub x: &'a [f64],
    pub inv_mass: &'a [f64],
    pub tag: Tags<'a>,
    pub types: &'a [c_int],
}

impl Atoms<'_> {
    pub fn len(&self) -> usize {
        self.inv_mass.len()
    }

    pub fn is_empty(&self) -> bool {
        self.inv_mass.is_empty()
    }

    /// `DPD_LAMMPS_OK` when every pair index is below `n`, the arrays (and `v`, `3 n`
    /// doubles) are long enough, every tag fits the noise key and every type lies in
    /// `1..=ntypes`; else the status of what is wrong.
    pub fn check(&self, pairs: &[[c_int; 2]], v_len: usize, ntypes: usize) -> c_int {
        let n = self.len();
        let bad_index = |k: c_int| usize::try_from(k).map_or(true, |k| k >= n);
        if pairs.iter().flatten().any(|&k| bad_index(k)) || self.x.len() < 3 * n || v_len < 3 * n {
            DPD_LAMMPS_INDEX
        } else if self.tag.len() < n || !self.tag.in_range() {
            DPD_LAMMPS_TAG
        } else if self.types.len() < n || !types_in_range(&self.types[..n], ntypes) {
            DPD_LAMMPS_TYPE
        } else {
            DPD_LAMMPS_OK
        }
    }

    /// The type of atom `k`, checked by [`Atoms::check`].
    #[inline(always)]
    pub fn type_of(&self, k: usize) -> usize {
        self.types[k] as usize
    }

    /// The position of atom `k` (one bounds check).
    #[inline(always)]
    fn position(&self, k: usize) -> [f64; 3] {
        let p = &self.x[3 * k..3 * k + 3];
        [p[0], p[1], p[2]]
    }

    /// The vector `x_i - x_j` and its square length.
    #[inline(always)]
    pub fn separation(&self, i: usize, j: usize) -> ([f64; 3], f64) {
        let (xi, xj) = (self.position(i), self.position(j));
        let d: [f64; 3] = std::array::from_fn(|k| xi[k] - xj[k]);
        (d, d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
    }
}

/// Whether every type lies in `1..=ntypes` (folded without branches, as [`Tags::in_range`]).
fn types_in_range(types: &[c_int], ntypes: usize) -> bool {
    let top = c_int::try_from(ntypes).unwrap_or(c_int::MAX);
    types.iter().fold(true, |ok, &t| ok & (t >= 1) & (t <= top))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indices_tags_and_types_are_checked() {
        let x = [0.0; 6];
        let atoms = |tag, types| Atoms {
            x: &x,
            inv_mass: &[1.0, 1.0],
            tag,
            types,
        };
        let ok = atoms(Tags::Small(&[1, 2]), &[1, 2]);
        assert_eq!(ok.check(&[[0, 1]], 6, 2), DPD_LAMMPS_OK);
        assert_eq!(ok.check(&[[0, 2]], 6, 2), DPD_LAMMPS_INDEX);
        assert_eq!(ok.check(&[[0, 1]], 5, 2), DPD_LAMMPS_INDEX);
        assert_eq!(ok.check(&[[0, 1]], 6, 1), DPD_LAMMPS_TYPE);
        let big = atoms(Tags::Big(&[1, 1 << 32]), &[1, 1]);
        assert_eq!(big.check(&[[0, 1]], 6, 1), DPD_LAMMPS_TAG);
        let widest = atoms(Tags::Big(&[1, u32::MAX as i64]), &[1, 1]);
        assert_eq!(widest.check(&[[0, 1]], 6, 1), DPD_LAMMPS_OK);
        assert_eq!(widest.tag.key(1), u32::MAX);
        assert_eq!(
            atoms(Tags::Small(&[-1, 2]), &[1, 1]).check(&[], 6, 1),
            DPD_LAMMPS_TAG
        );
        assert_eq!(
            atoms(Tags::Small(&[1, 2]), &[0, 1]).check(&[], 6, 1),
            DPD_LAMMPS_TYPE
        );
    }
}
