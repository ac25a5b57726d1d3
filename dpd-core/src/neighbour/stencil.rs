//! The distance tests of a cell against its half stencil.
//!
//! Testing the candidates of the stencil one by one, with a branch per candidate, spent most
//! of the scan in mispredicted branches and short loops (a row of three cells holds about nine
//! particles). Here the positions are first laid out as x, y and z columns in cell order
//! ([`Columns`], once per scan). For each cell its own particles, the cell above and the four
//! rows, each moved by its periodic shift, are copied from the columns into one stencil buffer
//! in steps of a fixed width (one step for almost every range, so the copy loops hardly ever
//! mispredict), and each particle of the cell is tested against the rest of its own cell and
//! the whole stencil in blocks: a loop the compiler vectorises computes in/out flags, a
//! branch-free loop gathers the hits, and only the hits reach the caller. On x86_64 CPUs with
//! AVX2 (detected at run time) the tests are compiled with AVX2 enabled; both paths compute
//! the same numbers (neither contracts multiply-adds).

use crate::system::on_all_threads;
use crate::Vec3;
use rayon::prelude::*;
use std::cell::RefCell;
use std::ops::Range;

/// Candidates tested per block.
const BLOCK: usize = 64;

/// Entries moved per step of [`Stencil::push`]: a row of three cells (about nine particles at
/// density 3) fits in one step.
const WIDTH: usize = 16;

/// Positions in cell order as separate x, y and z columns, followed by `WIDTH` zeros so that a
/// fixed-width copy may read past the last particle.
pub(super) struct Columns {
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
}

impl Columns {
    /// The columns of `pos`, filled on all threads for large systems.
    pub(super) fn new(pos: &[Vec3]) -> Self {
        let n = pos.len();
        let (mut x, mut y, mut z) = (
            vec![0.0; n + WIDTH],
            vec![0.0; n + WIDTH],
            vec![0.0; n + WIDTH],
        );
        let fill = |x: &mut [f64], y: &mut [f64], z: &mut [f64], pos: &[Vec3]| {
            for (((x, y), z), q) in x.iter_mut().zip(y).zip(z).zip(pos) {
                (*x, *y, *z) = (q.x, q.y, q.z);
            }
        };
        const CHUNK: usize = 4096;
        let (xs, ys, zs) = (&mut x[..n], &mut y[..n], &mut z[..n]);
        if on_all_threads(n) {
            xs.par_chunks_mut(CHUNK)
                .zip(ys.par_chunks_mut(CHUNK))
                .zip(zs.par_chunks_mut(CHUNK))
                .zip(pos.par_chunks(CHUNK))
                .for_each(|(((x, y), z), pos)| fill(x, y, z, pos));
        } else {
            fill(xs, ys, zs, pos);
        }
        Columns { x, y, z }
    }

    /// Position `k` (cell order).
    #[inline(always)]
    pub(super) fn position(&self, k: usize) -> Vec3 {
        Vec3::new(self.x[k], self.y[k], self.z[k])
    }
}

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
    /// Append the particles `range` (cell-order indices into `cols`), seen from a cell that
    /// must add `shift` to its positions to sit next to them.
    #[inline(always)]
    pub(super) fn push(&mut self, cols: &Columns, range: Range<usize>, shift: Vec3) {
        let (start, n) = (self.len, range.len());
        // The last step writes up to WIDTH - 1 entries past the end; the next push or the
        // length overwrites or ignores them.
        let room = start + n.next_multiple_of(WIDTH);
        if self.index.len() < room {
            let grown = room.next_power_of_two().max(256);
            self.x.resize(grown, 0.0);
            self.y.resize(grown, 0.0);
            self.z.resize(grown, 0.0);
            self.index.resize(grown, 0);
        }
        let mut k = 0;
        while k < n {
            let (from, to) = (
                range.start + k..range.start + k + WIDTH,
                start + k..start + k + WIDTH,
            );
            shifted(&mut self.x[to.clone()], &cols.x[from.clone()], shift.x);
            shifted(&mut self.y[to.clone()], &cols.y[from.clone()], shift.y);
            shifted(&mut self.z[to.clone()], &cols.z[from.clone()], shift.z);
            let index: &mut [u32; WIDTH] = (&mut self.index[to]).try_into().unwrap();
            for (l, i) in index.iter_mut().enumerate() {
                *i = (from.start + l) as u32;
            }
            k += WIDTH;
        }
        self.len = start + n;
    }

    /// Call `f(a, b, d)` for every particle `a` of `own` (in order) and every candidate `b`
    /// after `a` (in the order pushed) with `|d|^2 < cut2`, `d = q_a - (q_b - shift_b)`. The
    /// first push must have been the particles `own` themselves, unshifted: each particle
    /// meets the rest of its cell, then the other cells.
    #[inline(always)]
    pub(super) fn pairs(
        &self,
        cols: &Columns,
        own: Range<usize>,
        cut2: f64,
        f: &mut impl FnMut(u32, u32, Vec3),
    ) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the feature was detected.
            return unsafe { self.pairs_avx2(cols, own, cut2, f) };
        }
        self.pairs_portable(cols, own, cut2, f)
    }

    /// [`Stencil::pairs_portable`] compiled with AVX2.
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn pairs_avx2(
        &self,
        cols: &Columns,
        own: Range<usize>,
        cut2: f64,
        f: &mut impl FnMut(u32, u32, Vec3),
    ) {
        self.pairs_portable(cols, own, cut2, f)
    }

    #[inline(always)]
    fn pairs_portable(
        &self,
        cols: &Columns,
        own: Range<usize>,
        cut2: f64,
        f: &mut impl FnMut(u32, u32, Vec3),
    ) {
        let m = self.len;
        debug_assert!(own
            .clone()
            .eq(self.index[..own.len()].iter().map(|&i| i as usize)));
        // Written before they are read, block by block.
        let (mut inside, mut hits) = ([false; BLOCK], [0u8; BLOCK]);
        for (offset, a) in own.enumerate() {
            let qa = cols.position(a);
            let mut start = offset + 1;
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

/// `out[l] = column[l] - shift` for the first `WIDTH` entries of both.
#[inline(always)]
fn shifted(out: &mut [f64], column: &[f64], shift: f64) {
    // Loaded into a local first: the compiler cannot tell that `out` and `column` do not
    // overlap once this is inlined, and would copy element by element.
    let mut moved: [f64; WIDTH] = column.try_into().unwrap();
    for m in &mut moved {
        *m -= shift;
    }
    out.copy_from_slice(&moved);
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// The columns hold the positions followed by the zero padding, also when they are filled
    /// on several threads (above the size where the per-particle loops split).
    #[test]
    fn columns_are_the_positions_on_any_thread_count() {
        let mut rng = rand::rngs::StdRng::seed_from_u64(9);
        let pos: Vec<Vec3> = (0..20_000)
            .map(|_| Vec3::new(rng.random(), rng.random(), rng.random()))
            .collect();
        for threads in [1, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let cols = pool.install(|| Columns::new(&pos));
            for (k, column) in [&cols.x, &cols.y, &cols.z].into_iter().enumerate() {
                let want: Vec<f64> = pos.iter().map(|q| q[k]).collect();
                assert_eq!(column[..pos.len()], want[..], "axis {k}, {threads} threads");
                assert_eq!(
                    column[pos.len()..],
                    [0.0; WIDTH],
                    "padding, {threads} threads"
                );
            }
        }
    }

    /// Every path finds exactly the pairs a direct test finds, in the documented order, also
    /// when pushes span several copy steps and the stencil several blocks of candidates.
    #[test]
    fn blocks_find_the_pairs_in_order() {
        let mut rng = rand::rngs::StdRng::seed_from_u64(5);
        for candidates in [
            0,
            1,
            7,
            WIDTH,
            2 * WIDTH + 3,
            BLOCK - 1,
            BLOCK,
            3 * BLOCK + 5,
        ] {
            let pos: Vec<Vec3> = (0..candidates + 4)
                .map(|_| Vec3::new(rng.random(), rng.random(), rng.random()))
                .collect();
            let own = 0..4;
            // Two pushes of candidates with different shifts after the own cell.
            let middle = 4 + candidates / 3;
            let shift = |b: usize| {
                if b < middle {
                    Vec3::new(0.25, 0.0, -0.5)
                } else {
                    Vec3::new(0.0, -0.125, 0.0)
                }
            };
            let cut2 = 0.3;
            let mut want = Vec::new();
            for a in own.clone() {
                for b in a + 1..own.end {
                    let d = pos[a] - pos[b];
                    if d.norm_squared() < cut2 {
                        want.push((a as u32, b as u32, d));
                    }
                }
                for b in own.end..pos.len() {
                    let d = pos[a] - (pos[b] - shift(b));
                    if d.norm_squared() < cut2 {
                        want.push((a as u32, b as u32, d));
                    }
                }
            }
            let cols = Columns::new(&pos);
            with_stencil(|stencil| {
                stencil.push(&cols, own.clone(), Vec3::zeros());
                stencil.push(&cols, own.end..middle, shift(own.end));
                stencil.push(&cols, middle..pos.len(), shift(middle));
                let mut got = Vec::new();
                stencil.pairs(&cols, own.clone(), cut2, &mut |a, b, d| got.push((a, b, d)));
                assert_eq!(got, want, "{candidates} candidates");
                got.clear();
                stencil
                    .pairs_portable(&cols, own.clone(), cut2, &mut |a, b, d| got.push((a, b, d)));
                assert_eq!(got, want, "{candidates} candidates, portable");
            });
        }
    }
}
