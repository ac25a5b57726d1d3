//! The distance tests of a cell against its half stencil.
//!
//! Testing the candidates of the stencil one by one, with a branch per candidate, spent most
//! of the scan in mispredicted branches and short loops (a row of three cells holds about nine
//! particles). Here the candidates of the whole stencil (the cell above and the four rows,
//! each moved by its periodic shift) are copied once per cell into separate x, y and z
//! arrays, and each particle of the cell is tested against all of them in blocks: a loop the
//! compiler vectorises computes in/out flags, a branch-free loop gathers the hits, and only
//! the hits reach the caller. On x86_64 CPUs with AVX2 (detected at run time) the same code is
//! compiled with AVX2 enabled; both paths compute the same numbers (neither contracts
//! multiply-adds).

use crate::Vec3;
use std::cell::RefCell;
use std::ops::Range;

/// Candidates tested per block.
const BLOCK: usize = 64;

/// Candidates of one cell's stencil: position minus the periodic shift of its cell (so that
/// `q_a - candidate` is the separation from particle `a` of the cell), and cell-order index.
/// The first `len` entries of the arrays are in use; the arrays only grow.
#[derive(Default)]
pub(super) struct Stencil {
    len: usize,
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
    index: Vec<u32>,
}

thread_local! {
    /// One stencil buffer per thread, reused from cell to cell.
    static SCRATCH: RefCell<Stencil> = RefCell::new(Stencil::default());
}

/// Run `body` with this thread's stencil buffer, emptied.
pub(super) fn with_stencil<R>(body: impl FnOnce(&mut Stencil) -> R) -> R {
    SCRATCH.with(|s| {
        let mut s = s.borrow_mut();
        s.len = 0;
        body(&mut s)
    })
}

impl Stencil {
    /// Append the particles `range` of `pos` (cell order), seen from a cell that must add
    /// `shift` to its positions to sit next to them.
    #[inline(always)]
    pub(super) fn push(&mut self, pos: &[Vec3], range: Range<usize>, shift: Vec3) {
        let (start, end) = (self.len, self.len + range.len());
        if self.index.len() < end {
            let grown = end.next_power_of_two().max(256);
            self.x.resize(grown, 0.0);
            self.y.resize(grown, 0.0);
            self.z.resize(grown, 0.0);
            self.index.resize(grown, 0);
        }
        let slots = self.x[start..end]
            .iter_mut()
            .zip(&mut self.y[start..end])
            .zip(&mut self.z[start..end])
            .zip(&mut self.index[start..end]);
        for ((((x, y), z), index), (b, q)) in slots.zip(range.clone().zip(&pos[range])) {
            (*x, *y, *z, *index) = (q.x - shift.x, q.y - shift.y, q.z - shift.z, b as u32);
        }
        self.len = end;
    }

    /// Call `f(a, b, d)` for every particle `a` of `own` (in order) and every candidate `b`
    /// (in the order pushed) with `|d|^2 < cut2`, `d = q_a - (q_b - shift_b)`.
    #[inline(always)]
    pub(super) fn pairs(
        &self,
        pos: &[Vec3],
        own: Range<usize>,
        cut2: f64,
        f: &mut impl FnMut(u32, u32, Vec3),
    ) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the feature was detected.
            return unsafe { self.pairs_avx2(pos, own, cut2, f) };
        }
        self.pairs_portable(pos, own, cut2, f)
    }

    /// [`Stencil::pairs_portable`] compiled with AVX2.
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn pairs_avx2(
        &self,
        pos: &[Vec3],
        own: Range<usize>,
        cut2: f64,
        f: &mut impl FnMut(u32, u32, Vec3),
    ) {
        self.pairs_portable(pos, own, cut2, f)
    }

    #[inline(always)]
    fn pairs_portable(
        &self,
        pos: &[Vec3],
        own: Range<usize>,
        cut2: f64,
        f: &mut impl FnMut(u32, u32, Vec3),
    ) {
        let m = self.len;
        // Written before they are read, block by block.
        let (mut inside, mut hits) = ([false; BLOCK], [0u8; BLOCK]);
        for a in own {
            let qa = pos[a];
            let mut start = 0;
            while start < m {
                let end = (start + BLOCK).min(m);
                let (x, y, z) = (
                    &self.x[start..end],
                    &self.y[start..end],
                    &self.z[start..end],
                );
                for (((inside, &x), &y), &z) in inside.iter_mut().zip(x).zip(y).zip(z) {
                    let (dx, dy, dz) = (qa.x - x, qa.y - y, qa.z - z);
                    *inside = dx * dx + dy * dy + dz * dz < cut2;
                }
                // Every slot is written, the count advances only on a hit: no branch.
                let mut n = 0;
                for (k, &inside) in inside[..end - start].iter().enumerate() {
                    // n <= k < BLOCK, so the mask changes nothing; it spares a bounds check.
                    hits[n & (BLOCK - 1)] = k as u8;
                    n += inside as usize;
                }
                for &h in &hits[..n] {
                    let k = start + h as usize;
                    let d = Vec3::new(qa.x - self.x[k], qa.y - self.y[k], qa.z - self.z[k]);
                    f(a as u32, self.index[k], d);
                }
                start = end;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// Every path finds exactly the pairs a direct test finds, in the documented order, also
    /// when the stencil holds several blocks of candidates.
    #[test]
    fn blocks_find_the_pairs_in_order() {
        let mut rng = rand::rngs::StdRng::seed_from_u64(5);
        for candidates in [0, 1, 7, BLOCK - 1, BLOCK, BLOCK + 1, 3 * BLOCK + 5] {
            let pos: Vec<Vec3> = (0..candidates + 4)
                .map(|_| Vec3::new(rng.random(), rng.random(), rng.random()))
                .collect();
            let (own, shift) = (0..4, Vec3::new(0.25, 0.0, -0.5));
            let cut2 = 0.3;
            let mut want = Vec::new();
            for a in own.clone() {
                for b in 4..pos.len() {
                    let d = pos[a] - (pos[b] - shift);
                    if d.norm_squared() < cut2 {
                        want.push((a as u32, b as u32, d));
                    }
                }
            }
            with_stencil(|stencil| {
                stencil.push(&pos, 4..pos.len(), shift);
                let mut got = Vec::new();
                stencil.pairs(&pos, own.clone(), cut2, &mut |a, b, d| got.push((a, b, d)));
                assert_eq!(got, want, "{candidates} candidates");
                got.clear();
                stencil.pairs_portable(&pos, own.clone(), cut2, &mut |a, b, d| got.push((a, b, d)));
                assert_eq!(got, want, "{candidates} candidates, portable");
            });
        }
    }
}
