//! The conservative force of the plugin's pair style `dpd/soft`: DPD's soft repulsion alone
//! (dpd-core's [`Soft`]: force `a w` along `e_ij`, energy `a r_c w^2 / 2`, `w = 1 - r/r_c`),
//! per pair of atom types, over a LAMMPS half neighbour list.
//!
//! `pair dpd` with zero friction gives the same force but draws two random numbers per pair
//! that nothing uses; a scheme run by `fix dpd/split` gets its friction and noise from the fix,
//! so its conservative force needs none of that.
//!
//! LAMMPS conventions: atoms `0..nall` (owned, then ghosts), positions and forces as `3 nall`
//! contiguous doubles, types `1..=ntypes`, per type-pair values at `itype * (ntypes + 1) +
//! jtype`. A neighbour index carries the special-bond class in its top two bits (`j >> 30`),
//! which selects the factor of `special_lj` that scales the pair's force and energy. The list is
//! a half list with Newton's third law on: each pair appears once and both atoms (ghosts
//! included) receive its force, energy and virial halves.

use crate::abi::{slice, slice_mut};
use crate::record::PairRecord;
use crate::{DPD_LAMMPS_INDEX, DPD_LAMMPS_NULL, DPD_LAMMPS_OK, DPD_LAMMPS_TYPE};
use dpd_core::potential::Soft;
use std::ffi::c_int;

/// The bits of a neighbour index that hold the atom index (LAMMPS's `NEIGHMASK`).
const NEIGHMASK: c_int = 0x1FFF_FFFF;
/// The shift of the special-bond class in a neighbour index (LAMMPS's `SBBITS`).
const SBBITS: u32 = 30;

/// The coefficients of one pair style: per type pair the strength `a` and cutoff `r_c`, and
/// the factors of the special-bond classes.
pub struct SoftStyle<'a> {
    ntypes: usize,
    a: &'a [f64],
    rc: &'a [f64],
    special: [f64; 4],
}

/// What a force evaluation tallies besides the forces: the total energy and virial (xx, yy,
/// zz, xy, xz, yz) when asked for, and per atom the energy and the six virial components.
#[derive(Default)]
pub struct Tally<'a> {
    pub energy: Option<&'a mut f64>,
    pub virial: Option<&'a mut [f64; 6]>,
    pub eatom: Option<&'a mut [f64]>,
    pub vatom: Option<&'a mut [f64]>,
}

impl<'a> SoftStyle<'a> {
    /// The style of `ntypes` types with `a` and `rc` of `(ntypes + 1)^2` values each (row and
    /// column 0 unused) and the special-bond factors; `None` if a table is too short.
    pub fn new(ntypes: usize, a: &'a [f64], rc: &'a [f64], special: [f64; 4]) -> Option<Self> {
        let len = (ntypes + 1) * (ntypes + 1);
        (a.len() >= len && rc.len() >= len).then_some(SoftStyle {
            ntypes,
            a,
            rc,
            special,
        })
    }

    /// The number of atom types.
    pub fn ntypes(&self) -> usize {
        self.ntypes
    }

    /// The type of atom `k` as a table row, if `k` is an atom and its type in `1..=ntypes`.
    fn type_of(&self, types: &[c_int], k: usize) -> Option<usize> {
        let t = usize::try_from(*types.get(k)?).ok()?;
        (1..=self.ntypes).contains(&t).then_some(t)
    }

    /// The conservative force along `e_ij` between atoms of types `ti` and `tj` (in
    /// `1..=ntypes`) at distance `r`: `a_ij (1 - r/r_c,ij)`, 0 at and beyond the pair's
    /// cutoff, without special-bond factor (a T sweep's pairs carry none).
    pub fn pair_force_of_types(&self, ti: usize, tj: usize, r: f64) -> f64 {
        let pair = ti * (self.ntypes + 1) + tj;
        let rc = self.rc[pair];
        if r < rc {
            Soft::new(self.a[pair], rc).force(1.0 - r / rc)
        } else {
            0.0
        }
    }

    /// Add the forces between atom `i` and its `neighbours` (neighbour indices as LAMMPS
    /// stores them) to `f`, and their energy and virial to `tally`; with `record` (cleared for
    /// `n` atoms), add the pairs within the cutoff to it. `x` and `f` hold `3 n` doubles,
    /// `types` `n` values. Returns `DPD_LAMMPS_INDEX` (nothing added for this atom's remaining
    /// pairs) for an atom index or type out of range.
    #[allow(clippy::too_many_arguments)]
    pub fn atom(
        &self,
        i: usize,
        neighbours: &[c_int],
        x: &[f64],
        types: &[c_int],
        f: &mut [f64],
        tally: &mut Tally,
        record: Option<&mut PairRecord>,
    ) -> c_int {
        let n = types.len();
        let Some(ti) = self.type_of(types, i) else {
            return DPD_LAMMPS_INDEX;
        };
        if x.len() < 3 * n || f.len() < 3 * n {
            return DPD_LAMMPS_INDEX;
        }
        let xi = [x[3 * i], x[3 * i + 1], x[3 * i + 2]];
        let mut fi = [0.0; 3];
        let mut bucket = record.and_then(|r| r.begin(i));
        for &packed in neighbours {
            let factor = self.special[(packed >> SBBITS & 3) as usize];
            let j = (packed & NEIGHMASK) as usize;
            let Some(tj) = self.type_of(types, j) else {
                return DPD_LAMMPS_INDEX;
            };
            // A pair of factor 0 (special_bonds lj 0: excluded) has no force, and is not
            // recorded, so that the fix's sweeps exclude it too.
            if factor == 0.0 {
                continue;
            }
            let d = [xi[0] - x[3 * j], xi[1] - x[3 * j + 1], xi[2] - x[3 * j + 2]];
            let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            let pair = ti * (self.ntypes + 1) + tj;
            let rc = self.rc[pair];
            if r2 >= rc * rc || r2 == 0.0 {
                continue;
            }
            let r = r2.sqrt();
            let w = 1.0 - r / rc;
            if let Some(bucket) = bucket.as_mut() {
                bucket.push((i, j), r2, pair);
            }
            let soft = Soft::new(self.a[pair], rc);
            // The force on i is `fpair d`, on j `-fpair d`.
            let fpair = factor * soft.force(w) / r;
            for k in 0..3 {
                fi[k] += fpair * d[k];
                f[3 * j + k] -= fpair * d[k];
            }
            if let Some(energy) = tally.energy.as_deref_mut() {
                *energy += factor * soft.energy(w);
            }
            if let Some(eatom) = tally.eatom.as_deref_mut() {
                let half = 0.5 * factor * soft.energy(w);
                eatom[i] += half;
                eatom[j] += half;
            }
            if tally.virial.is_some() || tally.vatom.is_some() {
                let v = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)]
                    .map(|(a, b)| fpair * d[a] * d[b]);
                if let Some(virial) = tally.virial.as_deref_mut() {
                    virial.iter_mut().zip(v).for_each(|(s, c)| *s += c);
                }
                if let Some(vatom) = tally.vatom.as_deref_mut() {
                    for (c, value) in v.iter().enumerate() {
                        vatom[6 * i + c] += 0.5 * value;
                        vatom[6 * j + c] += 0.5 * value;
                    }
                }
            }
        }
        for k in 0..3 {
            f[3 * i + k] += fi[k];
        }
        DPD_LAMMPS_OK
    }
}

/// Add the `dpd/soft` forces over a LAMMPS half neighbour list to `f`: for each of the `inum`
/// atoms `i = ilist[ii]`, its `numneigh[i]` neighbours `firstneigh[i][..]`. `a` and `rc` hold
/// `(ntypes + 1)^2` doubles (see the module documentation), `special` 4; `x` and `f` `3 nall`
/// doubles, `types` `nall` ints. `energy` and `virial` (6 doubles) are null or totals to add to,
/// `eatom` (`nall` doubles) and `vatom` (`6 nall`) null or per-atom tallies to add to. Returns
/// `DPD_LAMMPS_OK`, `DPD_LAMMPS_NULL` for a null array that is needed, or `DPD_LAMMPS_INDEX`
/// for an atom index or type out of range (forces then partly added). `record` is null, or a
/// [`PairRecord`] that is cleared and given the pairs within its sweeps' cutoff, for the sweeps
/// that follow at these positions (`DPD_LAMMPS_TYPE`, nothing added, if its kernels have
/// another number of types).
///
/// # Safety
/// Every non-null pointer points to as many valid values as said above (`firstneigh[i]` to
/// `numneigh[i]` ints for each listed `i`; `ilist`, and `numneigh` and `firstneigh` indexed by
/// the values of `ilist`, must be valid for those reads); the written arrays overlap no other;
/// `record` is null or comes from `dpd_lammps_record_new`.
#[no_mangle]
pub unsafe extern "C" fn dpd_lammps_soft_forces(
    ntypes: c_int,
    a: *const f64,
    rc: *const f64,
    special: *const f64,
    inum: c_int,
    ilist: *const c_int,
    numneigh: *const c_int,
    firstneigh: *const *const c_int,
    nall: c_int,
    x: *const f64,
    types: *const c_int,
    f: *mut f64,
    energy: *mut f64,
    virial: *mut f64,
    eatom: *mut f64,
    vatom: *mut f64,
    record: *mut PairRecord,
) -> c_int {
    let (Ok(ntypes), Ok(inum), Ok(nall)) = (
        usize::try_from(ntypes),
        usize::try_from(inum),
        usize::try_from(nall),
    ) else {
        return DPD_LAMMPS_INDEX;
    };
    let table = (ntypes + 1) * (ntypes + 1);
    // SAFETY: the contract gives each array its length; the written ones overlap no other.
    let arrays = unsafe {
        (
            slice(a, table),
            slice(rc, table),
            slice(special.cast::<[f64; 4]>(), 1),
            slice(ilist, inum),
            slice(x, 3 * nall),
            slice(types, nall),
            slice_mut(f, 3 * nall),
        )
    };
    let (Some(a), Some(rc), Some(&[special]), Some(ilist), Some(x), Some(types), Some(f)) = arrays
    else {
        return DPD_LAMMPS_NULL;
    };
    if numneigh.is_null() || firstneigh.is_null() {
        return DPD_LAMMPS_NULL;
    }
    let Some(style) = SoftStyle::new(ntypes, a, rc, special) else {
        return DPD_LAMMPS_NULL;
    };
    // SAFETY: as above; null means not asked for.
    let mut tally = unsafe {
        Tally {
            energy: energy.as_mut(),
            virial: virial.cast::<[f64; 6]>().as_mut(),
            eatom: if eatom.is_null() {
                None
            } else {
                slice_mut(eatom, nall)
            },
            vatom: if vatom.is_null() {
                None
            } else {
                slice_mut(vatom, 6 * nall)
            },
        }
    };
    // SAFETY: the contract: null or a record of `dpd_lammps_record_new`, overlapping nothing.
    let mut record = unsafe { record.as_mut() };
    if let Some(record) = record.as_deref_mut() {
        // The record's type-pair slots are its kernels'.
        if record.ntypes() != ntypes {
            return DPD_LAMMPS_TYPE;
        }
        record.clear(nall);
    }
    for &i in ilist {
        let Ok(i) = usize::try_from(i) else {
            return DPD_LAMMPS_INDEX;
        };
        if i >= nall {
            return DPD_LAMMPS_INDEX;
        }
        // SAFETY: the contract: `numneigh[i]` and `firstneigh[i]` are valid for listed `i`, and
        // `firstneigh[i]` points to `numneigh[i]` ints.
        let neighbours = unsafe {
            let count = usize::try_from(*numneigh.add(i)).unwrap_or(0);
            slice(*firstneigh.add(i), count)
        };
        let Some(neighbours) = neighbours else {
            return DPD_LAMMPS_NULL;
        };
        let status = style.atom(
            i,
            neighbours,
            x,
            types,
            f,
            &mut tally,
            record.as_deref_mut(),
        );
        if status != DPD_LAMMPS_OK {
            return status;
        }
    }
    DPD_LAMMPS_OK
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two types; a = 25 within type 1, 40 across, cutoff 1 and 0.8 across.
    fn tables() -> (Vec<f64>, Vec<f64>) {
        let mut a = vec![0.0; 9];
        let mut rc = vec![0.0; 9];
        for (ti, tj, av, rv) in [(1, 1, 25.0, 1.0), (1, 2, 40.0, 0.8), (2, 2, 10.0, 1.0)] {
            a[ti * 3 + tj] = av;
            a[tj * 3 + ti] = av;
            rc[ti * 3 + tj] = rv;
            rc[tj * 3 + ti] = rv;
        }
        (a, rc)
    }

    /// Three atoms: 0 (type 1) and 1 (type 2) at r = 0.5, 0 and 2 (type 1) at r = 0.9 in a
    /// special-bond class of factor 0.5, 1 and 2 beyond the cross cutoff.
    fn atoms() -> (Vec<f64>, Vec<c_int>) {
        let x = vec![0.0, 0.0, 0.0, 0.3, 0.4, 0.0, 0.0, 0.0, 0.9];
        (x, vec![1, 2, 1])
    }

    /// Forces, energy and virial of each pair against `-dphi/dr` and `phi` written out here
    /// from algorithms.md section 1, with the special factor applied to the one pair it marks;
    /// total force zero (Newton's third law), per-atom tallies summing to the totals.
    #[test]
    fn forces_energy_and_virial_of_a_half_list() {
        let (a, rc) = tables();
        let (x, types) = atoms();
        let style = SoftStyle::new(2, &a, &rc, [1.0, 0.5, 1.0, 1.0]).unwrap();
        let mut f = vec![0.0; 9];
        let (mut energy, mut virial) = (0.0, [0.0; 6]);
        let (mut eatom, mut vatom) = (vec![0.0; 3], vec![0.0; 18]);
        let mut tally = Tally {
            energy: Some(&mut energy),
            virial: Some(&mut virial),
            eatom: Some(&mut eatom),
            vatom: Some(&mut vatom),
        };
        let neighbours = [1, 2 | 1 << SBBITS];
        assert_eq!(
            style.atom(0, &neighbours, &x, &types, &mut f, &mut tally, None),
            0
        );
        assert_eq!(style.atom(1, &[2], &x, &types, &mut f, &mut tally, None), 0);
        // Pair (0, 1): r = 0.5, r_c = 0.8, a = 40: force 40 (1 - 0.5/0.8) = 15 pushing 0 away
        // from 1 along -(0.6, 0.8); energy 40 * 0.8 / 2 * 0.375^2 = 2.25.
        // Pair (0, 2): r = 0.9, r_c = 1, a = 25, factor 0.5: force 0.5 * 2.5 = 1.25 along -z;
        // energy 0.5 * 12.5 * 0.01 = 0.0625.
        let expected_f0 = [-15.0 * 0.6, -15.0 * 0.8, -1.25];
        for k in 0..3 {
            assert!((f[k] - expected_f0[k]).abs() < 1e-12, "{f:?}");
            assert!((f[k] + f[3 + k] + f[6 + k]).abs() < 1e-12);
        }
        assert!((energy - (2.25 + 0.0625)).abs() < 1e-12, "{energy}");
        // Virial r_ij (x) F_ij: (0, 1) has r = -(0.3, 0.4, 0), F = 15 (-0.6, -0.8, 0); (0, 2)
        // has r = (0, 0, -0.9), F = (0, 0, -1.25).
        let expected = [0.3 * 9.0, 0.4 * 12.0, 0.9 * 1.25, 0.3 * 12.0, 0.0, 0.0];
        for (v, e) in virial.iter().zip(expected) {
            assert!((v - e).abs() < 1e-12, "{virial:?}");
        }
        assert!((eatom.iter().sum::<f64>() - energy).abs() < 1e-12);
        for c in 0..6 {
            let sum: f64 = (0..3).map(|k| vatom[6 * k + c]).sum();
            assert!((sum - virial[c]).abs() < 1e-12);
        }
    }

    /// A pair of special factor 0 gets no force and is left out of the record; the others are
    /// recorded with their geometry.
    #[test]
    fn pairs_of_factor_zero_are_excluded_and_not_recorded() {
        let (a, rc) = tables();
        let (x, types) = atoms();
        let style = SoftStyle::new(2, &a, &rc, [1.0, 0.0, 1.0, 1.0]).unwrap();
        let mut f = vec![0.0; 9];
        let kernels = crate::Kernels::new(1.0, 2.0, 2, &[4.5; 9], &rc).unwrap();
        let mut record = PairRecord::new(&kernels);
        record.colour_atoms(&[0, 0, 0]);
        record.clear(3);
        let neighbours = [1, 2 | 1 << SBBITS];
        let status = style.atom(
            0,
            &neighbours,
            &x,
            &types,
            &mut f,
            &mut Tally::default(),
            Some(&mut record),
        );
        assert_eq!(status, 0);
        assert_eq!(f[6..9], [0.0; 3], "{f:?}");
        assert_eq!(record.bucket(0, 3, 2), Some(&[[0, 1]][..]));
    }

    #[test]
    fn indices_and_types_out_of_range_are_refused() {
        let (a, rc) = tables();
        let (x, mut types) = atoms();
        let style = SoftStyle::new(2, &a, &rc, [1.0; 4]).unwrap();
        let mut f = vec![0.0; 9];
        let mut tally = Tally::default();
        assert_eq!(
            style.atom(0, &[3], &x, &types, &mut f, &mut tally, None),
            DPD_LAMMPS_INDEX
        );
        types[2] = 3;
        assert_eq!(
            style.atom(0, &[2], &x, &types, &mut f, &mut tally, None),
            DPD_LAMMPS_INDEX
        );
        assert!(SoftStyle::new(3, &a, &rc, [1.0; 4]).is_none());
    }

    /// The C entry point over a two-atom list gives the safe call's forces and refuses nulls.
    #[test]
    fn the_c_abi_walks_the_list() {
        let (a, rc) = tables();
        let (x, types) = atoms();
        let special = [1.0; 4];
        let ilist = [0, 1];
        let numneigh = [2, 1, 0];
        let (n0, n1) = ([1, 2], [2]);
        let firstneigh = [n0.as_ptr(), n1.as_ptr(), std::ptr::null()];
        let mut f = vec![0.0; 9];
        let mut energy = 0.0;
        let call = |f: &mut [f64], energy: *mut f64, x: *const f64| unsafe {
            dpd_lammps_soft_forces(
                2,
                a.as_ptr(),
                rc.as_ptr(),
                special.as_ptr(),
                2,
                ilist.as_ptr(),
                numneigh.as_ptr(),
                firstneigh.as_ptr(),
                3,
                x,
                types.as_ptr(),
                f.as_mut_ptr(),
                energy,
                std::ptr::null_mut(),
                std::ptr::null_mut(),
                std::ptr::null_mut(),
                std::ptr::null_mut(),
            )
        };
        assert_eq!(call(&mut f, &mut energy, x.as_ptr()), DPD_LAMMPS_OK);
        let style = SoftStyle::new(2, &a, &rc, special).unwrap();
        let mut g = vec![0.0; 9];
        let mut tally = Tally::default();
        style.atom(0, &n0, &x, &types, &mut g, &mut tally, None);
        style.atom(1, &n1, &x, &types, &mut g, &mut tally, None);
        assert_eq!(f, g);
        assert!((energy - (2.25 + 0.125)).abs() < 1e-12, "{energy}");
        assert_eq!(
            call(&mut f, std::ptr::null_mut(), std::ptr::null()),
            DPD_LAMMPS_NULL
        );
    }
}
