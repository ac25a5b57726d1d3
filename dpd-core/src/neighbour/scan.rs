//! The scan of a cell's pairs and the sweep over all cells in sweep order (see the module docs
//! of [`super`]).

use super::sliding::is_sliding;
use super::stencil::{with_stencil, Columns, Hits, Stencil};
use super::CellGrid;
use crate::avx2::with_avx2;
use crate::boundary::{LeesEdwards, PeriodicBox};
use crate::chunked::{self, Parts};
use crate::Vec3;
use std::ops::Range;

/// Below this many particles a sweep scans its units on one thread (at density 3 about
/// 12 000 pairs, where the pair passes split too).
const PARALLEL_MIN_PARTICLES: usize = 2048;

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

impl CellGrid {
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
pub(super) fn scan(
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

/// The rows `(dx, dy)` of the half stencil besides the own cell and the one above it: with the
/// three cells `dz = -1, 0, 1` of each, and `(0, 0, 1)`, they are one of each pair `{d, -d}`
/// of the 26 neighbour offsets.
const ROWS: [[isize; 2]; 4] = [[0, 1], [1, -1], [1, 0], [1, 1]];

/// Cell index `c + d` on a periodic axis of `n` cells, and the shift to add to a position in
/// cell `c` so that it sits next to the (unwrapped) image of cell `c + d`.
#[inline(always)]
pub(super) fn wrap_cell(c: usize, d: isize, n: usize, length: f64) -> (usize, f64) {
    let t = c as isize + d;
    if t < 0 {
        (n - 1, length)
    } else if t as usize >= n {
        (0, -length)
    } else {
        (t as usize, 0.0)
    }
}
