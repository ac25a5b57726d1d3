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
//! branch-free loop gathers the hits, and only the hits reach the caller. The sweep runs these
//! loops in code compiled with AVX2 where the CPU has it (`crate::avx2`).

use crate::parallel::on_all_threads;
use crate::Vec3;
use rayon::prelude::*;
use std::cell::RefCell;
use std::ops::Range;

/// Candidates tested per block, and the most hits handed on at once.
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
/// The first `len` entries of the arrays are in use; the arrays only grow. With them the
/// scratch of the tests, kept here so that no cell pays for setting it up.
#[derive(Default)]
pub(super) struct Stencil {
    len: usize,
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
    index: Vec<u32>,
    block: Box<Block>,
    pub(super) hits: Box<Hits>,
}

/// Which candidates of a block are hits.
struct Block {
    /// 1 for a hit, 0 else; whole groups of 8 past the block's end are 0 or masked off.
    inside: [u8; BLOCK],
    /// `at[s]`: the block position of hit `s` (and up to 7 bytes of scratch after the last).
    at: [u8; BLOCK + 8],
}

impl Default for Block {
    fn default() -> Self {
        Block {
            inside: [0; BLOCK],
            at: [0; BLOCK + 8],
        }
    }
}

/// For each set of hits among 8 candidates (bit `l` of the index for candidate `l`): their
/// positions 0 to 7 in ascending order, one per byte from the lowest, and their number.
const SPREAD: [(u64, u8); 256] = {
    let mut table = [(0, 0); 256];
    let mut mask = 0;
    while mask < 256 {
        let (mut positions, mut count, mut l) = (0u64, 0u8, 0);
        while l < 8 {
            if mask & (1 << l) != 0 {
                positions |= (l as u64) << (8 * count);
                count += 1;
            }
            l += 1;
        }
        table[mask] = (positions, count);
        mask += 1;
    }
    table
};

/// The hit bits of 8 flags (bytes 0 or 1, the first in the lowest byte of `flags`): the
/// multiplication moves byte `l`'s low bit to bit `56 + l`, without carries into those bits.
#[inline(always)]
fn hit_bits(flags: u64) -> usize {
    (flags.wrapping_mul(0x0102_0408_1020_4080) >> 56) as usize
}

thread_local! {
    /// One stencil buffer per thread, reused from cell to cell.
    static SCRATCH: RefCell<Stencil> = RefCell::new(Stencil::default());
}

/// Run `body` with this thread's stencil buffer, emptied.
pub(super) fn with_stencil<R>(body: impl FnOnce(&mut Stencil) -> R) -> R {
    SCRATCH.with(|s| {
        let mut s = s.borrow_mut();
        s.clear();
        body(&mut s)
    })
}

impl Stencil {
    /// Forget the candidates (the arrays keep their room).
    #[inline(always)]
    pub(super) fn clear(&mut self) {
        self.len = 0;
    }

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

    /// Call `f(hits)` for every particle `a` of `own` (in order) with its hits among the
    /// candidates after it (in the order pushed): those with `r2 = |d|^2 < cut2`,
    /// `d = q_a - (q_b - shift_b)`, at most `BLOCK` per call. The first push must have been
    /// the particles `own` themselves, unshifted: each particle meets the rest of its cell,
    /// then the other cells.
    #[inline(always)]
    pub(super) fn pairs(
        &mut self,
        cols: &Columns,
        own: Range<usize>,
        cut2: f64,
        f: &mut impl FnMut(&Hits),
    ) {
        let m = self.len;
        debug_assert!(own
            .clone()
            .eq(self.index[..own.len()].iter().map(|&i| i as usize)));
        let (block, hits) = (&mut *self.block, &mut *self.hits);
        for (offset, a) in own.enumerate() {
            let qa = cols.position(a);
            hits.a = a as u32;
            let mut start = offset + 1;
            while start < m {
                let end = (start + BLOCK).min(m);
                let len = end - start;
                let (x, y, z) = (
                    &self.x[start..end],
                    &self.y[start..end],
                    &self.z[start..end],
                );
                let Block { inside, at } = block;
                for (((inside, &x), &y), &z) in inside.iter_mut().zip(x).zip(y).zip(z) {
                    let (dx, dy, dz) = (qa.x - x, qa.y - y, qa.z - z);
                    *inside = u8::from(dx * dx + dy * dy + dz * dz < cut2);
                }
                // The hits' positions, 8 candidates at a time and without a branch: each
                // group's positions are stored whole at the count so far, which advances by
                // the group's hits (the next group overwrites the rest).
                let mut n = 0;
                for g in 0..len.div_ceil(8) {
                    let flags: [u8; 8] = inside[8 * g..8 * g + 8].try_into().unwrap();
                    // Candidates past the block's end are stale: masked off.
                    let valid = (1usize << (len - 8 * g).min(8)) - 1;
                    let (positions, count) = SPREAD[hit_bits(u64::from_le_bytes(flags)) & valid];
                    let positions = positions + 0x0808_0808_0808_0808 * g as u64;
                    // n <= 8 g, so the slots n..n + 8 are within the array.
                    at[n..n + 8].copy_from_slice(&positions.to_le_bytes());
                    n += count as usize;
                }
                let index = &self.index[start..end];
                for (slot, &k) in at[..n].iter().enumerate() {
                    let k = k as usize;
                    let (dx, dy, dz) = (qa.x - x[k], qa.y - y[k], qa.z - z[k]);
                    hits.b[slot] = index[k];
                    (hits.dx[slot], hits.dy[slot], hits.dz[slot]) = (dx, dy, dz);
                    hits.r2[slot] = dx * dx + dy * dy + dz * dz;
                }
                hits.len = n;
                if n > 0 {
                    hits.set_distances();
                    f(hits);
                }
                start = end;
            }
        }
    }
}

/// The hits of one particle `a` among a stretch of candidates, in candidate order: their
/// cell-order indices `b`, the separations `d = q_a - q_b` (minimum image) by component,
/// `r2 = |d|^2`, `r = sqrt(r2)` and `1 / r`, in arrays whose first [`Hits::len`] entries are
/// set (at most 64). The square roots and divisions are computed for all hits at once, in
/// vector registers.
#[derive(Clone, Debug)]
pub struct Hits {
    pub(crate) a: u32,
    len: usize,
    pub(crate) b: [u32; BLOCK],
    pub(crate) dx: [f64; BLOCK],
    pub(crate) dy: [f64; BLOCK],
    pub(crate) dz: [f64; BLOCK],
    pub(crate) r2: [f64; BLOCK],
    pub(crate) r: [f64; BLOCK],
    pub(crate) inv_r: [f64; BLOCK],
}

impl Default for Hits {
    fn default() -> Self {
        Hits {
            a: 0,
            len: 0,
            b: [0; BLOCK],
            dx: [0.0; BLOCK],
            dy: [0.0; BLOCK],
            dz: [0.0; BLOCK],
            r2: [0.0; BLOCK],
            r: [0.0; BLOCK],
            inv_r: [0.0; BLOCK],
        }
    }
}

impl Hits {
    /// The most hits handed on at once.
    pub const CAPACITY: usize = BLOCK;

    /// The particle the hits are partners of.
    pub fn a(&self) -> u32 {
        self.a
    }

    /// Number of hits.
    #[inline(always)]
    #[allow(clippy::len_without_is_empty)]
    pub fn len(&self) -> usize {
        self.len
    }

    /// Partner `k` and its separation `q_a - q_b`.
    #[inline(always)]
    pub fn get(&self, k: usize) -> (u32, Vec3) {
        (self.b[k], Vec3::new(self.dx[k], self.dy[k], self.dz[k]))
    }

    /// The single hit `(a, b)` at separation `d`.
    #[inline(always)]
    pub(super) fn set_one(&mut self, a: u32, b: u32, d: Vec3) {
        (self.a, self.len, self.b[0]) = (a, 1, b);
        (self.dx[0], self.dy[0], self.dz[0]) = (d.x, d.y, d.z);
        self.r2[0] = d.x * d.x + d.y * d.y + d.z * d.z;
        self.set_distances();
    }

    /// `r` and `1 / r` from `r2` (`1 / r` infinite for coincident particles).
    #[inline(always)]
    fn set_distances(&mut self) {
        let n = self.len;
        let (r, inv_r) = (&mut self.r[..n], &mut self.inv_r[..n]);
        for ((r, inv_r), &r2) in r.iter_mut().zip(inv_r).zip(&self.r2[..n]) {
            *r = r2.sqrt();
            *inv_r = 1.0 / *r;
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
        let mut rng = rand_chacha::ChaCha12Rng::seed_from_u64(9);
        let pos: Vec<Vec3> = (0..20_000)
            .map(|_| Vec3::new(rng.random(), rng.random(), rng.random()))
            .collect();
        for threads in [1, 3] {
            let cols = crate::on_threads(threads, || Columns::new(&pos));
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

    /// For each of the 256 sets of hits among 8 candidates, `hit_bits` recovers the set from
    /// the flags and `SPREAD` lists its positions in order.
    #[test]
    fn hit_bits_and_spread_list_every_set_of_flags() {
        for (mask, &(positions, count)) in SPREAD.iter().enumerate() {
            let flags: [u8; 8] = std::array::from_fn(|l| u8::from(mask & (1 << l) != 0));
            assert_eq!(hit_bits(u64::from_le_bytes(flags)), mask);
            let listed: Vec<usize> = (0..count as usize)
                .map(|s| (positions >> (8 * s)) as usize & 0xFF)
                .collect();
            let want: Vec<usize> = (0..8).filter(|l| mask & (1 << l) != 0).collect();
            assert_eq!(listed, want, "mask {mask:08b}");
        }
    }

    /// Every path finds exactly the pairs a direct test finds, in the documented order, also
    /// when pushes span several copy steps and the stencil several blocks of candidates.
    #[test]
    fn blocks_find_the_pairs_in_order() {
        let mut rng = rand_chacha::ChaCha12Rng::seed_from_u64(5);
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
                let collect = |got: &mut Vec<(u32, u32, Vec3)>, h: &Hits| {
                    for k in 0..h.len() {
                        let (b, d) = h.get(k);
                        assert_eq!(h.r2[k], d.norm_squared());
                        assert_eq!(h.r[k], d.norm());
                        got.push((h.a(), b, d));
                    }
                };
                let mut got = Vec::new();
                stencil.pairs(&cols, own.clone(), cut2, &mut |h| collect(&mut got, h));
                assert_eq!(got, want, "{candidates} candidates");
                let mut avx2 = Vec::new();
                crate::avx2::with_avx2(|| {
                    stencil.pairs(&cols, own.clone(), cut2, &mut |h| collect(&mut avx2, h))
                });
                assert_eq!(
                    avx2, want,
                    "{candidates} candidates, in AVX2 code where available"
                );
            });
        }
    }
}
