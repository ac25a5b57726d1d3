//! Binning into cells, the cell order and the colouring of units (see the module docs of
//! [`super`]).

use super::CellGrid;
use crate::boundary::PeriodicBox;
use crate::disjoint::Disjoint;
use crate::parallel::on_all_threads;
use crate::Vec3;
use rayon::prelude::*;
use std::ops::Range;

/// Layers along x of `n` cells that fit, and the colour modulus `m` for them: the largest count
/// in `n - 2 ..= n` (at least 3) with a divisor `m` in `2 ..= 5`, `m` the smallest such; else
/// `n` with its smallest divisor from 2 on. Layers `k m` apart (cyclically) are then at least
/// two layers apart, and the half stencil reaches one layer along x, so the layers of one
/// colour touch disjoint particles.
pub(super) fn colourable(n: usize) -> (usize, usize) {
    for count in (n.saturating_sub(2).max(3)..=n).rev() {
        if let Some(m) = (2..=5).find(|&m| count.is_multiple_of(m)) {
            return (count, m);
        }
    }
    (n, (2..=n).find(|&m| n.is_multiple_of(m)).unwrap_or(n))
}

/// Blocks a layer of `ny` cells is split into along y: an even number (two colours) of blocks
/// of four to seven cells when that gives at least four, so that a colour has more units to
/// share among threads; else 1 (whole layers). Two blocks of one colour are then separated by
/// a block of at least two cells, more than the stencil's reach of one cell to either side.
pub(super) fn y_blocks(ny: usize) -> usize {
    let blocks = 2 * (ny / 8);
    if blocks >= 4 {
        blocks
    } else {
        1
    }
}

impl CellGrid {
    /// Bin `q` into cells of edge >= `min_cell` and return the cell order: `order[k]` is the
    /// index in `q` of the k-th particle in cell order (cells by index, within a cell by index
    /// in `q`). Cell counts are rounded down by at most two to counts the colouring divides
    /// (the private `colourable`). With fewer than 3 cells along some axis the grid degenerates
    /// to one cell (all pairs are then searched: O(N^2), only for boxes smaller than three
    /// cutoffs).
    ///
    /// The scans below read positions in this order: pass `q` permuted by `order` (as a
    /// [`crate::System`] stores them after a build) or [`CellGrid::gather`]ed.
    pub fn bin(&mut self, q: &[Vec3], bx: &PeriodicBox, min_cell: f64) -> &[u32] {
        let l = bx.lengths();
        let fit = |k: usize| {
            let n = (l[k] / min_cell).floor();
            if n.is_finite() && n >= 3.0 {
                (n as usize).min(1 << 10)
            } else {
                1
            }
        };
        let mut dims = [fit(0), fit(1), fit(2)];
        let coloured = !dims.contains(&1);
        let (moduli, y_blocks) = if coloured {
            let (nx, mx) = colourable(dims[0]);
            dims[0] = nx;
            let blocks = y_blocks(dims[1]);
            ([mx, if blocks > 1 { 2 } else { 1 }], blocks)
        } else {
            dims = [1, 1, 1];
            ([1, 1], 1)
        };
        if dims != self.dims || moduli != self.moduli || self.sweep.is_empty() {
            self.dims = dims;
            self.moduli = moduli;
            self.y_blocks = y_blocks;
            self.coloured = coloured;
            self.plan_sweep();
        }
        let ncell = self.cells();
        let per_length = [0, 1, 2].map(|k| dims[k] as f64 / l[k]);
        let last = [0, 1, 2].map(|k| (dims[k] - 1) as f64);
        let cell_of = |x: &Vec3| {
            let mut c = 0usize;
            for k in 0..3 {
                // Clamped before the conversion (NaN to 0: `max` takes the number), which
                // then needs no saturation; the upper clamp keeps rounding at L in range.
                let ck = (x[k] * per_length[k]).max(0.0).min(last[k]);
                // SAFETY: ck is finite and in [0, dims[k] - 1], below 2^10.
                c = c * dims[k] + unsafe { ck.to_int_unchecked::<u32>() } as usize;
            }
            c
        };
        // A stable counting sort in chunks of particles, one per thread: each chunk finds
        // and counts its particles' cells, the counts give every (cell, chunk) its slots in
        // order, and the chunks fill their slots on all threads; the order is that of the
        // serial sort.
        let parallel = on_all_threads(q.len());
        let threads = if parallel {
            rayon::current_num_threads()
        } else {
            1
        };
        let chunk = q.len().div_ceil(threads).max(1);
        let mut cell = vec![0u32; q.len()];
        let count = |(part, cell): (&[Vec3], &mut [u32])| {
            let mut counts = vec![0u32; ncell];
            for (x, c) in part.iter().zip(cell) {
                *c = cell_of(x) as u32;
                counts[*c as usize] += 1;
            }
            counts
        };
        let mut slots: Vec<Vec<u32>> = if parallel {
            q.par_chunks(chunk)
                .zip(cell.par_chunks_mut(chunk))
                .map(count)
                .collect()
        } else {
            q.chunks(chunk)
                .zip(cell.chunks_mut(chunk))
                .map(count)
                .collect()
        };
        self.cell_start.clear();
        self.cell_start.resize(ncell + 1, 0);
        let mut next = 0;
        for c in 0..ncell {
            self.cell_start[c] = next;
            for counts in slots.iter_mut() {
                let n = counts[c];
                counts[c] = next;
                next += n;
            }
        }
        self.cell_start[ncell] = next;
        self.order.clear();
        self.order.resize(q.len(), 0);
        let order = Disjoint::new(&mut self.order);
        let fill = |(k, (slots, cell)): (usize, (&mut Vec<u32>, &[u32]))| {
            for (i, &c) in (k * chunk..).zip(cell) {
                let slot = &mut slots[c as usize];
                // SAFETY: the chunks own disjoint slots.
                unsafe { *order.get(*slot as usize) = i as u32 };
                *slot += 1;
            }
        };
        if parallel {
            slots
                .par_iter_mut()
                .zip(cell.par_chunks(chunk))
                .enumerate()
                .for_each(fill);
        } else {
            slots
                .iter_mut()
                .zip(cell.chunks(chunk))
                .enumerate()
                .for_each(fill);
        }
        &self.order
    }

    /// Cells, units and colours in sweep order for the current `dims` (see the module docs).
    fn plan_sweep(&mut self) {
        let [nx, ny, nz] = self.dims;
        let [mx, my] = self.moduli;
        let blocks = self.y_blocks;
        let block_start = |b: usize| b * ny / blocks;
        self.sweep.clear();
        self.units = vec![0];
        self.colour_units = vec![0];
        for colour in 0..mx * my {
            for cx in (colour / my..nx).step_by(mx) {
                for b in (colour % my..blocks).step_by(my) {
                    // A unit's cells are consecutive indices: one layer, rows of full z.
                    let cells =
                        (cx * ny + block_start(b)) * nz..(cx * ny + block_start(b + 1)) * nz;
                    self.sweep.extend(cells.map(|c| c as u32));
                    self.units.push(self.sweep.len() as u32);
                }
            }
            self.colour_units.push(self.units.len() as u32 - 1);
        }
    }

    /// `q` permuted into the cell order of the last [`CellGrid::bin`].
    pub fn gather(&self, q: &[Vec3]) -> Vec<Vec3> {
        self.order.iter().map(|&i| q[i as usize]).collect()
    }

    /// Number of cells.
    pub fn cells(&self) -> usize {
        self.dims.iter().product()
    }

    /// Whether cells of one colour own disjoint pairs (see the module docs).
    pub fn is_coloured(&self) -> bool {
        self.coloured
    }

    /// Number of colours: the product of the moduli (1 when the grid is not coloured).
    pub fn colours(&self) -> usize {
        self.moduli.iter().product()
    }

    /// Colour of cell `c`, in `0..colours()`: `(cx mod m_x) m_y + (y-block of cy) mod m_y`.
    pub fn colour(&self, c: usize) -> usize {
        let [mx, my] = self.moduli;
        let (cx, cy, _) = self.coordinates(c);
        // The block b with b ny / blocks <= cy < (b + 1) ny / blocks.
        let block = ((cy + 1) * self.y_blocks - 1) / self.dims[1];
        (cx % mx) * my + block % my
    }

    /// Cell-order indices of the particles of cell `c`.
    #[inline(always)]
    pub(super) fn range(&self, c: usize) -> Range<usize> {
        self.cell_start[c] as usize..self.cell_start[c + 1] as usize
    }

    /// `(cx, cy, cz)` of cell `c`.
    #[inline(always)]
    pub(super) fn coordinates(&self, c: usize) -> (usize, usize, usize) {
        let [_, ny, nz] = self.dims;
        (c / (ny * nz), (c / nz) % ny, c % nz)
    }
}
