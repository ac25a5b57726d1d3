//! The interacting pairs of the current positions, with the geometry every sub-flow needs,
//! and the executor that visits them in the sweep order of [`crate::neighbour`].

use crate::boundary::PeriodicBox;
use crate::neighbour::{Runs, VerletList};
use crate::params::Params;
use crate::Vec3;
use dpd_ir::SweepOrder;
use rayon::prelude::*;
use std::marker::PhantomData;

/// One interacting pair with `r_ij < r_c`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pair {
    pub i: u32,
    pub j: u32,
    /// Unit vector from j to i (minimum image).
    pub e: Vec3,
    /// Distance `r_ij`.
    pub r: f64,
    /// `w = 1 - r / r_c`, the conservative-force weight.
    pub w: f64,
    /// Random weight `w_R = w^(s/2)`; the dissipative weight is `w_R^2`.
    pub wr: f64,
}

/// Below this many pairs a sweep is not worth splitting across threads.
const PARALLEL_MIN_PAIRS: usize = 8192;

/// The interacting pairs in sweep order, grouped into cell runs and colours.
#[derive(Clone, Debug, Default)]
pub struct PairTable {
    pairs: Vec<Pair>,
    groups: Runs,
}

impl std::ops::Deref for PairTable {
    type Target = [Pair];
    fn deref(&self) -> &[Pair] {
        &self.pairs
    }
}

impl<'a> IntoIterator for &'a PairTable {
    type Item = &'a Pair;
    type IntoIter = std::slice::Iter<'a, Pair>;
    fn into_iter(self) -> Self::IntoIter {
        self.pairs.iter()
    }
}

impl PairTable {
    /// Refill with the pairs of `list` that interact at positions `q`, keeping its order.
    ///
    /// Coincident particles (`r = 0`) have no defined direction; such a pair is left out, so it
    /// exerts no force rather than a NaN one.
    pub(crate) fn collect(
        &mut self,
        list: &VerletList,
        q: &[Vec3],
        bx: &PeriodicBox,
        params: &Params,
    ) {
        let rc = params.rc();
        let rc2 = rc * rc;
        let inv_rc = 1.0 / rc;
        let from = list.groups();
        self.pairs.clear();
        self.groups.runs.clear();
        self.groups.runs.push(0);
        for run in from.runs.windows(2) {
            for &(i, j) in &list.candidates()[run[0] as usize..run[1] as usize] {
                let d = bx.min_image(q[i as usize] - q[j as usize]);
                let r2 = d.norm_squared();
                if r2 < rc2 && r2 > 0.0 {
                    let r = r2.sqrt();
                    let w = 1.0 - r * inv_rc;
                    self.pairs.push(Pair {
                        i,
                        j,
                        e: d / r,
                        r,
                        w,
                        wr: params.w_r(w),
                    });
                }
            }
            self.groups.runs.push(self.pairs.len() as u32);
        }
        self.groups.colours.clone_from(&from.colours);
        self.groups.independent = from.independent;
    }

    /// Visit every pair once in the sweep order (`Forward`), or in exactly the reverse order
    /// (`Reverse`). Runs of one colour go to different threads when the grid is coloured and
    /// the table is large; they touch disjoint particles, so the result is the same as the
    /// sequential visit on any number of threads.
    pub(crate) fn visit(&self, order: SweepOrder, visit: impl Fn(&Pair) + Sync) {
        let g = &self.groups;
        let run = |k: u32| {
            let pairs = &self.pairs[g.runs[k as usize] as usize..g.runs[k as usize + 1] as usize];
            match order {
                SweepOrder::Forward => pairs.iter().for_each(&visit),
                SweepOrder::Reverse => pairs.iter().rev().for_each(&visit),
            }
        };
        let parallel = g.independent
            && self.pairs.len() >= PARALLEL_MIN_PAIRS
            && rayon::current_num_threads() > 1;
        let colours = g.colours.len().saturating_sub(1);
        for step in 0..colours {
            let c = match order {
                SweepOrder::Forward => step,
                SweepOrder::Reverse => colours - 1 - step,
            };
            let runs = g.colours[c]..g.colours[c + 1];
            if parallel {
                runs.into_par_iter().for_each(run);
            } else {
                match order {
                    SweepOrder::Forward => runs.for_each(run),
                    SweepOrder::Reverse => runs.rev().for_each(run),
                }
            }
        }
    }
}

/// A slice written concurrently at disjoint indices.
///
/// Safety contract of [`Disjoint::get`]: no two threads access the same index at the same
/// time. [`PairTable::visit`] guarantees it for the two particles of a pair, because
/// concurrently visited runs own pairs of disjoint particle sets.
pub(crate) struct Disjoint<'a, T> {
    ptr: *mut T,
    len: usize,
    _slice: PhantomData<&'a mut [T]>,
}

unsafe impl<T: Send> Sync for Disjoint<'_, T> {}

impl<'a, T> Disjoint<'a, T> {
    pub(crate) fn new(slice: &'a mut [T]) -> Self {
        Disjoint {
            ptr: slice.as_mut_ptr(),
            len: slice.len(),
            _slice: PhantomData,
        }
    }

    /// # Safety
    /// No other reference to element `i` may be alive while the returned one is.
    #[inline(always)]
    #[allow(clippy::mut_from_ref)]
    pub(crate) unsafe fn get(&self, i: usize) -> &mut T {
        assert!(i < self.len, "index {i} out of bounds ({})", self.len);
        // SAFETY: in bounds (checked above); exclusivity is the caller's contract.
        unsafe { &mut *self.ptr.add(i) }
    }
}
