//! Neighbour search in O(N): a cell grid, and a Verlet list with a skin built from it.
//!
//! # Particle order
//!
//! The grid bins particles into cells and returns the cell order (a stable counting sort). A
//! [`crate::System`] stores its particles in that order, re-sorted at every list build, so that
//! the particles of a cell and of a row of cells along z are contiguous in memory: the cell
//! scan reads positions sequentially and the pair loops touch nearby memory. Particles keep
//! their identity through [`crate::System::ids`].
//!
//! # Sweep order
//!
//! The Verlet list fixes the order in which every pairwise sub-flow visits the pairs. Cells of
//! edge at least `r_c + skin` own the pairs between themselves and 13 of their neighbours (a
//! half stencil spanning offsets `[0, 1] x [-1, 1] x [-1, 1]`). The cells are grouped into
//! units that one thread sweeps in turn: a unit is a layer of cells `cx` (all `cy`, all `cz`),
//! or, when a layer has at least 16 cells along y, a block of four to seven consecutive `cy`
//! of a layer (an even number of blocks, all `cz`). A unit's cells are consecutive cell
//! indices, so its particles are one range of memory. Units are coloured by
//! `(cx mod m_x) m_y + b mod m_y`, `b` the block index, with `m_x` the smallest divisor from 2
//! to 5 of the layer count (which is rounded down by at most two layers to have one) and
//! `m_y = 2` (1 with whole layers). The half stencil reaches one layer along x and one cell to
//! either side along y, so two units of one colour, at least two layers apart or separated by
//! a block of at least two cells, touch disjoint particles and can be processed concurrently.
//! The order is: colours in order, within a colour units by ascending `(cx, b)`, within a unit
//! cells by ascending index, within a cell the pairs in scan order: particle by particle `a`
//! of the cell in cell order, its pairs with the later particles `b > a` of the cell, then
//! with the stencil: the cell above along z, then the rows `(dx, dy) = (0, 1), (1, -1),
//! (1, 0), (1, 1)`, each row its cells `dz = -1, 0, 1` in storage order. (The cell and its
//! stencil are copied once per cell and tested in vectorised blocks, see `stencil.rs`. Pairs
//! that share a particle are in the same relative order as when all pairs within the cell come
//! first and the stencil is then scanned range by range for all particles of the cell, so these
//! orders give the same results.)
//! Within a colour, units commute, so this order gives the same result on any number of
//! threads. A sweep in units keeps the particles it touches close together: consecutive cells
//! share most of their stencils, and a colour reads each particle at most about once, so a
//! pass reads the particle arrays a few times (two to four colours) where a colouring of
//! single cells (18 to 125 colours) read most of them once per colour.
//! Where the box is too small for the grid (fewer than 3 cells along some axis) there is one
//! cell and one colour, and processing is sequential.
//!
//! The order is a function of the positions at the last build; a checkpoint stores those
//! positions so that a restarted run rebuilds the same list. The list is rebuilt when a particle
//! has moved more than `skin / 2` since the last build; with skin 0 it is rebuilt whenever
//! the positions changed, and keeps neither candidates nor reference positions.
//!
//! # Lees-Edwards
//!
//! Under a sliding boundary ([`LeesEdwards`]) with a non-zero offset, the cells across the y
//! boundary are misaligned along x. Then the cells of the top row (`cy = n_y - 1`) own all
//! pairs with the images of the bottom row: for each `dz` the four image cells that overlap the
//! x-range `[cx - 1, cx + 2)` cell widths, scanned in order of increasing x. The bottom row
//! drops its stencil rows that cross downwards. Two top-row cells of one colour may
//! reach the same bottom cell, so these crossing runs form an extra colour after the others,
//! visited sequentially (`Runs::colours` then has one more group than the grid has colours). Everything else keeps the periodic order;
//! with offset 0 (in particular shear rate 0) the list is exactly the periodic one. Positions
//! that crossed the y boundary since the build carry the offset of their crossing, so the
//! rebuild test allows for the distance `travel` the images slid since the build: it rebuilds
//! when a particle moved more than `(skin - 3 travel) / 2` (one travel for the displacement of
//! each particle of a pair, one for the slide between them).

mod stencil;

use crate::avx2::with_avx2;
use crate::boundary::{LeesEdwards, PeriodicBox};
use crate::chunked::{self, Parts};
use crate::disjoint::Disjoint;
use crate::system::on_all_threads;
use crate::Vec3;
use rayon::prelude::*;
use std::ops::Range;
pub use stencil::Hits;
use stencil::{with_stencil, Columns, Stencil};

/// Particles binned into cells of edge at least `min_cell`, and the sweep over their pairs.
#[derive(Clone, Debug, Default)]
pub struct CellGrid {
    dims: [usize; 3],
    /// Colour moduli of the layer index `cx` and of the y-block index (see the module docs);
    /// all 1 when not coloured.
    moduli: [usize; 2],
    /// Blocks each layer is split into along y (1: a unit is a whole layer).
    y_blocks: usize,
    coloured: bool,
    /// `cell_start[c]..cell_start[c + 1]`: cell-order indices of the particles of cell `c`.
    cell_start: Vec<u32>,
    /// `order[k]`: input index of the k-th particle in cell order.
    order: Vec<u32>,
    /// Cells in sweep order (colour by colour, unit by unit); `units[u]..units[u + 1]` are the
    /// positions in `sweep` of the cells of unit `u`, `colour_units[c]..colour_units[c + 1]`
    /// the units of colour `c`. They depend on `dims` only and are kept between builds.
    sweep: Vec<u32>,
    units: Vec<u32>,
    colour_units: Vec<u32>,
}

/// Below this many particles a sweep scans its units on one thread (at density 3 about
/// 12 000 pairs, where the pair passes split too).
const PARALLEL_MIN_PARTICLES: usize = 2048;

/// Layers along x of `n` cells that fit, and the colour modulus `m` for them: the largest count
/// in `n - 2 ..= n` (at least 3) with a divisor `m` in `2 ..= 5`, `m` the smallest such; else
/// `n` with its smallest divisor from 2 on. Layers `k m` apart (cyclically) are then at least
/// two layers apart, and the half stencil reaches one layer along x, so the layers of one
/// colour touch disjoint particles.
fn colourable(n: usize) -> (usize, usize) {
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
fn y_blocks(ny: usize) -> usize {
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

    /// Call `f(hits)` with the pairs owned by cell `c` whose minimum-image separation
    /// `d = q_a - q_b` is shorter than `cutoff` (`cutoff` at most the cell edge of the last
    /// bin), in scan order, except the pairs that cross a sliding boundary (see
    /// [`CellGrid::for_each_sliding_pair_of_cell`]): one call per particle `a` and block of
    /// its candidates. `a`, `b` and the positions of `scan` are in cell order; `stencil` is
    /// scratch.
    ///
    /// Periodic images come from a per-row shift instead of a minimum-image test per pair.
    #[inline(always)]
    fn for_each_pair_of_cell(
        &self,
        c: usize,
        stencil: &mut Stencil,
        scan: &Scan,
        mut f: impl FnMut(&Hits),
    ) {
        let Scan {
            ref cols,
            bx,
            shear,
            cutoff,
        } = *scan;
        let cut2 = cutoff * cutoff;
        let own = self.range(c);
        if self.dims == [1, 1, 1] {
            let image = |d: Vec3| match shear {
                None => bx.min_image(d),
                Some(le) => le.min_image(bx, d).0,
            };
            for a in own.clone() {
                for b in a + 1..own.end {
                    let d = image(cols.position(a) - cols.position(b));
                    if d.norm_squared() < cut2 {
                        stencil.hits.set_one(a as u32, b as u32, d);
                        f(&stencil.hits);
                    }
                }
            }
            return;
        }
        let sliding = is_sliding(shear);
        let [nx, ny, nz] = self.dims;
        let (cx, cy, cz) = self.coordinates(c);
        let l = bx.lengths();
        stencil.clear();
        {
            // The own cell first, then the one above: one range unless that one wraps.
            if cz + 1 < nz {
                let both = own.start..self.cell_start[c + 2] as usize;
                stencil.push(cols, both, Vec3::zeros());
            } else {
                stencil.push(cols, own.clone(), Vec3::zeros());
                let (z, sz) = wrap_cell(cz, 1, nz, l.z);
                let above = self.range((cx * ny + cy) * nz + z);
                stencil.push(cols, above, Vec3::new(0.0, 0.0, sz));
            }
            for [dx, dy] in ROWS {
                let (y, sy) = wrap_cell(cy, dy, ny, l.y);
                if sliding && sy != 0.0 {
                    continue;
                }
                let (x, sx) = wrap_cell(cx, dx, nx, l.x);
                let row = (x * ny + y) * nz;
                if cz >= 1 && cz + 1 < nz {
                    let cells = self.cell_start[row + cz - 1] as usize
                        ..self.cell_start[row + cz + 2] as usize;
                    stencil.push(cols, cells, Vec3::new(sx, sy, 0.0));
                } else {
                    for dz in [-1, 0, 1] {
                        let (z, sz) = wrap_cell(cz, dz, nz, l.z);
                        stencil.push(cols, self.range(row + z), Vec3::new(sx, sy, sz));
                    }
                }
            }
            stencil.pairs(cols, own, cut2, &mut f);
        }
    }

    /// Call `f(a, b, d)` for the pairs that cell `c` owns across a sliding Lees-Edwards
    /// boundary (none unless `c` is in the top row and the offset is non-zero): pairs with the
    /// images, one box up, of the bottom row's cells that overlap the x-range
    /// `[cx - 1, cx + 2)` cell widths, for `dz` in -1, 0, 1 and those cells in order of x.
    pub fn for_each_sliding_pair_of_cell(
        &self,
        c: usize,
        pos: &[Vec3],
        bx: &PeriodicBox,
        le: &LeesEdwards,
        cutoff: f64,
        mut f: impl FnMut(u32, u32, Vec3),
    ) {
        let [nx, ny, nz] = self.dims;
        let (cx, cy, cz) = self.coordinates(c);
        if !is_sliding(Some(le)) || self.dims == [1, 1, 1] || cy + 1 != ny {
            return;
        }
        let cut2 = cutoff * cutoff;
        let own = self.range(c);
        let l = bx.lengths();
        // The image of bottom cell k starts at x = (k + s + frac) w, s + frac = offset / w.
        let s = (le.offset() * nx as f64 / l.x).floor() as isize;
        for dz in [-1, 0, 1] {
            let (z, sz) = wrap_cell(cz, dz, nz, l.z);
            for t in 0..4 {
                // Unwrapped bottom-cell index K = k + m n_x whose image overlaps the range.
                let big_k = cx as isize - s - 2 + t;
                let k = big_k.rem_euclid(nx as isize) as usize;
                let m = big_k.div_euclid(nx as isize) as f64;
                let shift = Vec3::new(-(le.offset() + m * l.x), -l.y, sz);
                scan(pos, &own, self.range(k * ny * nz + z), shift, cut2, &mut f);
            }
        }
    }

    /// Call `f(a, b, d)` once for every unordered pair closer than `cutoff`, cell by cell
    /// (`a`, `b` and `pos` in cell order, `d` the minimum-image `q_a - q_b`).
    pub fn for_each_pair(
        &self,
        pos: &[Vec3],
        bx: &PeriodicBox,
        shear: Option<&LeesEdwards>,
        cutoff: f64,
        mut f: impl FnMut(u32, u32, Vec3),
    ) {
        let scan = Scan::new(pos, bx, shear, cutoff);
        for c in 0..self.cells() {
            with_stencil(|stencil| {
                let each = |h: &Hits| {
                    for k in 0..h.len() {
                        let (b, d) = h.get(k);
                        f(h.a, b, d);
                    }
                };
                self.for_each_pair_of_cell(c, stencil, &scan, each)
            });
            if let Some(le) = shear {
                self.for_each_sliding_pair_of_cell(c, pos, bx, le, cutoff, &mut f);
            }
        }
    }

    /// All pairs within `cutoff` in the sweep order of the module docs: `emit(hits, out)` is
    /// called with them, a particle's hits among a block of candidates at a time (cell-order
    /// indices into `pos`, separations the minimum-image `q_a - q_b`), and may push any number
    /// of items into `out`. After the last cell of a unit, `after(run)` is called with the
    /// unit's items, and with the items of each top-row cell across a sliding boundary. Units
    /// are scanned colour by colour, those of one colour on all threads, and joined in order,
    /// so the result does not depend on the thread count, and `after` may update the particles
    /// of its run's pairs (concurrent runs share no particle). `items` is refilled (its
    /// allocation reused); returns the grouping into runs and colours.
    #[allow(clippy::too_many_arguments)]
    pub fn sweep<T: Send>(
        &self,
        pos: &[Vec3],
        bx: &PeriodicBox,
        shear: Option<&LeesEdwards>,
        cutoff: f64,
        items: &mut Parts<T>,
        emit: impl Fn(&Hits, &mut Vec<T>) + Sync,
        after: impl Fn(&[T]) + Sync,
    ) -> Runs {
        // Every index handed on lies in a cell range of the last bin, so below pos.len().
        assert_eq!(
            pos.len(),
            self.order.len(),
            "positions are not those of the last bin"
        );
        let scan = Scan::new(pos, bx, shear, cutoff);
        let units: Vec<Range<usize>> = self
            .units
            .windows(2)
            .map(|u| u[0] as usize..u[1] as usize)
            .collect();
        let parallel = pos.len() >= PARALLEL_MIN_PARTICLES;
        let (groups, split) = (
            &self.colour_units,
            if self.coloured { self.colours() } else { 0 },
        );
        let found =
            chunked::flat_map_ordered(&units, groups, split, items, parallel, |unit, out| {
                let start = out.len();
                with_stencil(|stencil| {
                    with_avx2(|| {
                        for &c in &self.sweep[unit.clone()] {
                            let (c, emit) = (c as usize, |h: &Hits| emit(h, out));
                            self.for_each_pair_of_cell(c, stencil, &scan, emit);
                        }
                    })
                });
                after(&out[start..]);
            });
        let mut groups = Runs {
            runs: vec![0],
            colours: vec![0],
            independent: if self.coloured { self.colours() } else { 0 },
        };
        let mut end = 0;
        for colour in self.colour_units.windows(2) {
            for &n in &found[colour[0] as usize..colour[1] as usize] {
                end += n;
                if n > 0 {
                    groups.runs.push(end);
                }
            }
            groups.colours.push(groups.runs.len() as u32 - 1);
        }
        if let Some(le) = shear.filter(|le| le.offset() != 0.0) {
            let (base, runs) = (items.len(), &mut groups.runs);
            items.append(|part| {
                let mut hits = Hits::default();
                // Only top-row cells own such pairs; the others find none.
                for c in 0..self.cells() {
                    let start = part.len();
                    self.for_each_sliding_pair_of_cell(c, pos, bx, le, cutoff, |a, b, d| {
                        hits.set_one(a, b, d);
                        emit(&hits, part)
                    });
                    after(&part[start..]);
                    let end = (base + part.len()) as u32;
                    if end != *runs.last().unwrap_or(&0) {
                        runs.push(end);
                    }
                }
            });
            groups.colours.push(groups.runs.len() as u32 - 1);
        }
        groups
    }

    /// Cell-order indices of the particles of cell `c`.
    #[inline(always)]
    fn range(&self, c: usize) -> Range<usize> {
        self.cell_start[c] as usize..self.cell_start[c + 1] as usize
    }

    /// `(cx, cy, cz)` of cell `c`.
    #[inline(always)]
    fn coordinates(&self, c: usize) -> (usize, usize, usize) {
        let [_, ny, nz] = self.dims;
        (c / (ny * nz), (c / nz) % ny, c % nz)
    }
}

/// What a scan of cells reads: the positions in cell order (as columns), the box and its
/// sliding boundary, and the cutoff.
struct Scan<'a> {
    cols: Columns,
    bx: &'a PeriodicBox,
    shear: Option<&'a LeesEdwards>,
    cutoff: f64,
}

impl<'a> Scan<'a> {
    fn new(pos: &[Vec3], bx: &'a PeriodicBox, shear: Option<&'a LeesEdwards>, cutoff: f64) -> Self {
        Scan {
            cols: Columns::new(pos),
            bx,
            shear,
            cutoff,
        }
    }
}

/// Call `f(a, b, d)` for the pairs between the particles `own`, moved by `shift`, and the
/// particles `other` (cell-order indices into `pos`) closer than `sqrt(cut2)`, with
/// `d = q_a + shift - q_b`.
#[inline(always)]
fn scan(
    pos: &[Vec3],
    own: &Range<usize>,
    other: Range<usize>,
    shift: Vec3,
    cut2: f64,
    f: &mut impl FnMut(u32, u32, Vec3),
) {
    let start = other.start;
    let others = &pos[other];
    for a in own.clone() {
        let qa = pos[a] + shift;
        for (b, qb) in others.iter().enumerate() {
            let d = qa - qb;
            if d.norm_squared() < cut2 {
                f(a as u32, (start + b) as u32, d);
            }
        }
    }
}

/// Whether `shear` slides the images out of alignment (non-zero offset).
#[inline(always)]
fn is_sliding(shear: Option<&LeesEdwards>) -> bool {
    shear.is_some_and(|le| le.offset() != 0.0)
}

/// The rows `(dx, dy)` of the half stencil besides the own cell and the one above it: with the
/// three cells `dz = -1, 0, 1` of each, and `(0, 0, 1)`, they are one of each pair `{d, -d}`
/// of the 26 neighbour offsets.
const ROWS: [[isize; 2]; 4] = [[0, 1], [1, -1], [1, 0], [1, 1]];

/// Cell index `c + d` on a periodic axis of `n` cells, and the shift to add to a position in
/// cell `c` so that it sits next to the (unwrapped) image of cell `c + d`.
#[inline(always)]
fn wrap_cell(c: usize, d: isize, n: usize, length: f64) -> (usize, f64) {
    let t = c as isize + d;
    if t < 0 {
        (n - 1, length)
    } else if t as usize >= n {
        (0, -length)
    } else {
        (t as usize, 0.0)
    }
}

/// Pairs grouped for the sweep order: `runs[k]..runs[k + 1]` is the k-th run of pairs (those
/// of a unit of cells, or of a top-row cell across a sliding boundary),
/// `colours[c]..colours[c + 1]` the runs of colour `c`. The runs of each of the first
/// `independent` colours touch disjoint particles (0: none do); runs of a further colour (the
/// pairs across a sliding Lees-Edwards boundary) never count as independent.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Runs {
    pub runs: Vec<u32>,
    pub colours: Vec<u32>,
    pub independent: usize,
}

/// Verlet list with a skin, in sweep order, rebuilt on displacement.
///
/// A build has two halves: [`VerletList::bin`] bins the positions and returns the cell order,
/// the owner puts its particles in that order, then [`VerletList::build`] scans them. With skin
/// 0 the list keeps no candidates: the owner takes the pairs straight from
/// [`VerletList::grid`]'s sweep.
#[derive(Clone, Debug)]
pub struct VerletList {
    skin: f64,
    reference: Vec<Vec3>,
    /// The sliding boundary at the last build (its offset fixed the sweep order).
    shear: Option<LeesEdwards>,
    candidates: Parts<(u32, u32)>,
    groups: Runs,
    grid: CellGrid,
    /// Whether a build matches the positions (with skin 0 cleared by
    /// [`VerletList::positions_changed`]; with a skin the displacement test decides).
    built: bool,
    builds: u64,
}

impl VerletList {
    /// An empty list with the given skin (length units, >= 0).
    pub fn new(skin: f64) -> Self {
        VerletList {
            skin,
            reference: Vec::new(),
            shear: None,
            candidates: Parts::default(),
            groups: Runs::default(),
            grid: CellGrid::default(),
            built: false,
            builds: 0,
        }
    }

    pub fn skin(&self) -> f64 {
        self.skin
    }

    /// Number of builds so far.
    pub fn builds(&self) -> u64 {
        self.builds
    }

    /// Positions of the last build (empty before the first, and always with skin 0).
    pub fn reference(&self) -> &[Vec3] {
        &self.reference
    }

    /// The sliding boundary at the last build (`None` before the first or without shear).
    pub fn reference_shear(&self) -> Option<&LeesEdwards> {
        self.shear.as_ref()
    }

    /// The grid of the last build.
    pub fn grid(&self) -> &CellGrid {
        &self.grid
    }

    /// First half of a build: bin `q` for cutoff `rc` and return the cell order (see
    /// [`CellGrid::bin`]).
    pub fn bin(&mut self, q: &[Vec3], bx: &PeriodicBox, rc: f64) -> &[u32] {
        self.grid.bin(q, bx, rc + self.skin)
    }

    /// Second half of a build, after [`VerletList::bin`]: `q` are the positions in the cell
    /// order it returned. Candidate indices are indices into `q`.
    pub fn build(&mut self, q: &[Vec3], bx: &PeriodicBox, shear: Option<&LeesEdwards>, rc: f64) {
        if self.skin > 0.0 {
            let push = |h: &Hits, out: &mut Vec<(u32, u32)>| {
                out.extend(h.b[..h.len()].iter().map(|&b| (h.a, b)))
            };
            let reach = rc + self.skin;
            self.groups = self
                .grid
                .sweep(q, bx, shear, reach, &mut self.candidates, push, |_| {});
            self.reference.clear();
            self.reference.extend_from_slice(q);
        }
        self.shear = shear.copied();
        self.built = true;
        self.builds += 1;
    }

    /// The positions moved: with skin 0 the list is stale.
    pub fn positions_changed(&mut self) {
        if self.skin == 0.0 {
            self.built = false;
        }
    }

    /// Forget the build (the particle order it refers to is gone).
    pub fn invalidate(&mut self) {
        self.built = false;
    }

    /// Whether the list must be rebuilt for positions `q`.
    pub fn needs_rebuild(&self, q: &[Vec3], bx: &PeriodicBox, shear: Option<&LeesEdwards>) -> bool {
        if !self.built {
            return true;
        }
        if self.skin == 0.0 {
            return shear.map(LeesEdwards::offset) != self.shear.as_ref().map(LeesEdwards::offset);
        }
        if q.len() != self.reference.len() {
            return true;
        }
        match (shear, &self.shear) {
            (None, None) => self.moved_too_far(q, self.skin, |d| bx.min_image(d)),
            (Some(now), Some(then)) => {
                let reach = self.skin - 3.0 * (now.travel() - then.travel()).abs();
                reach < 0.0 || self.moved_too_far(q, reach, |d| now.min_image(bx, d).0)
            }
            _ => true,
        }
    }

    /// Whether a particle moved more than `reach / 2` since the last build, displacements
    /// measured by `image`.
    fn moved_too_far(&self, q: &[Vec3], reach: f64, image: impl Fn(Vec3) -> Vec3) -> bool {
        let limit = 0.25 * reach * reach;
        q.iter().zip(&self.reference).any(|(a, b)| {
            let d2 = image(a - b).norm_squared();
            d2 > limit || d2.is_nan()
        })
    }

    /// Candidate pairs within `r_c + skin` at the last build, in sweep order (none with skin 0).
    pub fn candidates(&self) -> &Parts<(u32, u32)> {
        &self.candidates
    }

    /// Grouping of [`VerletList::candidates`] into runs and colours.
    pub fn groups(&self) -> &Runs {
        &self.groups
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::init::uniform_positions;

    fn brute(q: &[Vec3], cut: f64, image: impl Fn(Vec3) -> Vec3) -> Vec<(u32, u32)> {
        let mut v = Vec::new();
        for i in 0..q.len() {
            for j in i + 1..q.len() {
                if image(q[i] - q[j]).norm() < cut {
                    v.push((i as u32, j as u32));
                }
            }
        }
        v
    }

    /// Both halves of a build, as a system does them; returns the positions in cell order.
    fn build(
        list: &mut VerletList,
        q: &[Vec3],
        bx: &PeriodicBox,
        shear: Option<&LeesEdwards>,
    ) -> Vec<Vec3> {
        list.bin(q, bx, 1.0);
        let pos = list.grid().gather(q);
        list.build(&pos, bx, shear, 1.0);
        pos
    }

    /// The list holds exactly the brute-force pairs, and runs of one of the independent colours
    /// share no particle.
    fn check_list(list: &VerletList, expected: Vec<(u32, u32)>, coloured: bool, what: &str) {
        let mut got: Vec<(u32, u32)> = list
            .candidates()
            .iter()
            .map(|&(i, j)| (i.min(j), i.max(j)))
            .collect();
        got.sort_unstable();
        assert_eq!(got, expected, "{what}");
        let g = list.groups();
        assert_eq!(g.independent > 0, coloured, "{what}");
        {
            for c in 0..g.independent {
                let mut seen = std::collections::HashMap::new();
                for k in g.colours[c]..g.colours[c + 1] {
                    let run = g.runs[k as usize]..g.runs[k as usize + 1];
                    for &(i, j) in list
                        .candidates()
                        .slice(run.start as usize..run.end as usize)
                    {
                        for p in [i, j] {
                            assert_eq!(
                                *seen.entry(p).or_insert(k),
                                k,
                                "{what}: particle {p} in two runs of colour {c}"
                            );
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn colourable_counts_lose_at_most_two_layers() {
        assert_eq!(colourable(3), (3, 3));
        assert_eq!(colourable(5), (5, 5));
        assert_eq!(colourable(7), (6, 2));
        assert_eq!(colourable(20), (20, 2));
        assert_eq!(colourable(13), (12, 2));
        for n in 3..200 {
            let (count, m) = colourable(n);
            assert!(count + 2 >= n && count <= n && count.is_multiple_of(m) && m >= 2);
        }
    }

    /// Blocks along y: none below 16 cells, else an even number of blocks of four to seven
    /// cells; the units of the sweep are each cell exactly once, colour by colour.
    #[test]
    fn units_cover_every_cell_once() {
        assert_eq!(y_blocks(15), 1);
        for ny in 16..200 {
            let b = y_blocks(ny);
            assert!(b >= 4 && b.is_multiple_of(2), "{ny} cells: {b} blocks");
            assert!(
                (4..=7).contains(&(ny / b)) && ny.div_ceil(b) <= 7,
                "{ny} cells: {b} blocks"
            );
        }
        for lengths in [
            [5.5, 5.5, 5.5],
            [20.0, 20.0, 20.0],
            [7.3, 17.2, 4.1],
            [2.0, 9.0, 9.0],
        ] {
            let bx = PeriodicBox::new(lengths).unwrap();
            let mut grid = CellGrid::default();
            grid.bin(&uniform_positions(&bx, 100, 1), &bx, 1.0);
            let mut cells = grid.sweep.clone();
            cells.sort_unstable();
            assert_eq!(
                cells,
                (0..grid.cells() as u32).collect::<Vec<_>>(),
                "{lengths:?}"
            );
            for (c, colour) in grid.colour_units.windows(2).enumerate() {
                let units = colour[0] as usize..colour[1] as usize;
                let cells = grid.units[units.start] as usize..grid.units[units.end] as usize;
                let wrong = grid.sweep[cells]
                    .iter()
                    .find(|&&k| grid.colour(k as usize) != c);
                assert_eq!(wrong, None, "{lengths:?}: colour {c}");
            }
        }
    }

    #[test]
    fn cell_order_is_a_stable_sort_by_cell() {
        let bx = PeriodicBox::new([7.0, 9.1, 6.3]).unwrap();
        let q = uniform_positions(&bx, 500, 3);
        let mut grid = CellGrid::default();
        let order = grid.bin(&q, &bx, 1.3).to_vec();
        let mut seen = order.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..500).collect::<Vec<u32>>());
        // Binning the sorted positions again gives the identity.
        let pos = grid.gather(&q);
        assert_eq!(grid.bin(&pos, &bx, 1.3), (0..500).collect::<Vec<u32>>());
    }

    #[test]
    fn parallel_binning_is_the_serial_stable_sort() {
        let bx = PeriodicBox::cubic(20.0).unwrap();
        let q = uniform_positions(&bx, 24_000, 4);
        let on = |threads| {
            crate::on_threads(threads, || {
                let mut grid = CellGrid::default();
                (grid.bin(&q, &bx, 1.0).to_vec(), grid.cell_start.clone())
            })
        };
        let (serial, starts) = on(1);
        // One chunk per thread; with 7 the last chunk is shorter than the others.
        for threads in [2, 3, 7] {
            assert_eq!(
                on(threads),
                (serial.clone(), starts.clone()),
                "{threads} threads"
            );
        }
        // Stable: within a cell, ascending input index.
        for c in starts.windows(2) {
            let cell = &serial[c[0] as usize..c[1] as usize];
            assert!(cell.windows(2).all(|w| w[0] < w[1]));
        }
    }

    #[test]
    fn verlet_list_matches_brute_force_and_colours_are_disjoint() {
        // Cells of edge >= 1.3: box 5.3 has 4 x 5 x 3 (layer colours 2), 9.5 has 6 x 9 x 6 (7
        // layers rounded down to 6), the last 5 x 17 x 4 (layer colours 5, four blocks along y).
        let boxes = [
            ([2.5, 3.25, 2.25], false),
            ([4.2, 5.46, 3.78], false),
            ([5.3, 6.89, 4.77], true),
            ([6.0, 7.8, 5.4], true),
            ([7.0, 9.1, 6.3], true),
            ([9.5, 12.35, 8.55], true),
            ([7.0, 22.5, 5.5], true),
        ];
        for (lengths, coloured) in boxes {
            let (bx, l) = (PeriodicBox::new(lengths).unwrap(), lengths[0]);
            let q = uniform_positions(&bx, 400, 1);
            let mut list = VerletList::new(0.3);
            let pos = build(&mut list, &q, &bx, None);
            let expected = brute(&pos, 1.3, |d| bx.min_image(d));
            check_list(&list, expected, coloured, &format!("box {l}"));
            assert_eq!(list.groups().colours.len(), list.grid().colours() + 1);
        }
    }

    #[test]
    fn sliding_list_matches_brute_force() {
        // Offsets aligned with the cells (0), slightly off, and arbitrary; grids of 3, 4 and
        // more cells along x (3 and 4 are where the four image cells wrap around).
        let boxes = [
            ([2.5, 3.25, 2.25], false),
            ([4.2, 4.5, 4.5], true),
            ([5.3, 6.9, 4.8], true),
            ([7.0, 9.1, 6.3], true),
            ([9.5, 12.35, 8.55], true),
            ([7.0, 22.5, 5.5], true),
        ];
        for (lengths, coloured) in boxes {
            let bx = PeriodicBox::new(lengths).unwrap();
            let l = lengths[0];
            let q = uniform_positions(&bx, 400, 2);
            for offset in [0.0, 1e-9, 0.37 * l, 0.999 * l] {
                let le = LeesEdwards::restore(0.3, offset, 0.0, &bx).unwrap();
                let mut list = VerletList::new(0.3);
                let pos = build(&mut list, &q, &bx, Some(&le));
                let expected = brute(&pos, 1.3, |d| le.min_image(&bx, d).0);
                check_list(
                    &list,
                    expected,
                    coloured,
                    &format!("box {l}, offset {offset}"),
                );
                let colours = list.groups().colours.len() - 1;
                assert_eq!(colours, list.grid().colours() + usize::from(offset != 0.0));
            }
        }
    }

    #[test]
    fn rebuilds_only_after_half_skin() {
        let bx = PeriodicBox::cubic(5.0).unwrap();
        let mut q = vec![Vec3::new(1.0, 1.0, 1.0), Vec3::new(2.0, 1.0, 1.0)];
        let mut list = VerletList::new(0.4);
        assert!(list.needs_rebuild(&q, &bx, None));
        build(&mut list, &q, &bx, None);
        q[0].x += 0.19;
        assert!(!list.needs_rebuild(&q, &bx, None));
        q[0].x += 0.02;
        assert!(list.needs_rebuild(&q, &bx, None));
    }

    #[test]
    fn without_skin_rebuilds_when_positions_change() {
        let bx = PeriodicBox::cubic(5.0).unwrap();
        let q = vec![Vec3::new(1.0, 1.0, 1.0), Vec3::new(2.0, 1.0, 1.0)];
        let mut list = VerletList::new(0.0);
        build(&mut list, &q, &bx, None);
        assert!(!list.needs_rebuild(&q, &bx, None));
        assert!(list.candidates().is_empty() && list.reference().is_empty());
        list.positions_changed();
        assert!(list.needs_rebuild(&q, &bx, None));
    }

    #[test]
    fn sliding_images_shorten_the_rebuild_interval() {
        // After the images slid by 0.1, the skin 0.4 leaves (0.4 - 0.3) / 2 = 0.05 of
        // displacement.
        let bx = PeriodicBox::cubic(5.0).unwrap();
        let mut le = LeesEdwards::new(0.1).unwrap();
        let mut q = vec![Vec3::new(1.0, 1.0, 1.0), Vec3::new(2.0, 1.0, 1.0)];
        let mut list = VerletList::new(0.4);
        build(&mut list, &q, &bx, Some(&le));
        le.advance(&bx, 0.2);
        q[0].x += 0.04;
        assert!(!list.needs_rebuild(&q, &bx, Some(&le)));
        q[0].x += 0.02;
        assert!(list.needs_rebuild(&q, &bx, Some(&le)));
    }
}
