//! Neighbour search in O(N): a cell grid, and a Verlet list with a skin built from it.
//!
//! # Sweep order
//!
//! The Verlet list fixes the order in which every pairwise sub-flow visits the pairs. Cells of
//! edge at least `r_c + skin` own the pairs between themselves and 13 of their neighbours (a
//! half stencil spanning offsets `[0, 1] x [-1, 1] x [-1, 1]`). Cells are coloured by
//! `(cx mod 2, cy mod 3, cz mod 3)`: two cells of one colour are at least two cells apart
//! along x or three along y or z, so the pairs they own share no particle and can be processed
//! concurrently. The order is: colours 0..18, within a colour cells by ascending index, within
//! a cell the pairs in scan order (own pairs `(a, b)` with `a < b` in cell order, then the
//! stencil neighbours in a fixed order). Within a colour, cells commute, so this order gives the
//! same result on any number of threads. Where the box is too small for the colouring (fewer
//! than 4 cells along x or 3 along y or z, or counts that are not multiples of 2 and 3 after
//! rounding down) there is one colour and processing is sequential.
//!
//! The order is a function of the positions at the last build; a checkpoint stores those
//! positions so that a restarted run rebuilds the same list. The list is rebuilt when a particle
//! has moved more than `skin / 2` since the last build.
//!
//! # Lees-Edwards
//!
//! Under a sliding boundary ([`LeesEdwards`]) with a non-zero offset, the cells across the y
//! boundary are misaligned along x. Then the cells of the top row (`cy = n_y - 1`) own all
//! pairs with the images of the bottom row: for each `dz` the four image cells that overlap the
//! x-range `[cx - 1, cx + 2)` cell widths, scanned in order of increasing x. The bottom row
//! drops its three stencil entries that cross downwards. Two top-row cells of one colour may
//! reach the same bottom cell, so these crossing runs form an extra colour after the 18, visited
//! sequentially (`Runs::colours` then has 19 groups). Everything else keeps the periodic order;
//! with offset 0 (in particular shear rate 0) the list is exactly the periodic one. Positions
//! that crossed the y boundary since the build carry the offset of their crossing, so the
//! rebuild test allows for the distance `travel` the images slid since the build: it rebuilds
//! when a particle moved more than `(skin - 3 travel) / 2` (one travel for the displacement of
//! each particle of a pair, one for the slide between them).

use crate::boundary::{LeesEdwards, PeriodicBox};
use crate::chunked;
use crate::Vec3;

/// Particles binned into cells of edge at least `min_cell`.
#[derive(Clone, Debug, Default)]
pub struct CellGrid {
    dims: [usize; 3],
    coloured: bool,
    /// `cell_start[c]..cell_start[c + 1]` indexes `members` for cell `c`.
    cell_start: Vec<u32>,
    members: Vec<u32>,
    cell_of: Vec<u32>,
    /// Positions gathered in cell order.
    sorted: Vec<Vec3>,
}

/// Colours of the cell colouring, `2 * 3 * 3`.
pub const COLOURS: usize = 18;

impl CellGrid {
    /// Bin `q` into cells of edge >= `min_cell`; cell counts are rounded down to multiples of
    /// (2, 3, 3) where that keeps at least (4, 3, 3) cells, which makes the grid colourable. With
    /// fewer than 3 cells along some axis the grid degenerates to one cell (all pairs are then
    /// searched: O(N^2), only for boxes smaller than three cutoffs).
    pub fn build(&mut self, q: &[Vec3], bx: &PeriodicBox, min_cell: f64) {
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
        if dims.contains(&1) {
            dims = [1, 1, 1];
        }
        let coloured = dims[0] >= 4 && dims[1] >= 3 && dims[2] >= 3;
        if coloured {
            dims = [dims[0] / 2 * 2, dims[1] / 3 * 3, dims[2] / 3 * 3];
        }
        self.dims = dims;
        self.coloured = coloured;
        let ncell = dims[0] * dims[1] * dims[2];
        self.cell_of.clear();
        self.cell_of.extend(q.iter().map(|x| {
            let mut c = 0usize;
            for k in 0..3 {
                // `as usize` saturates (NaN -> 0); the clamp keeps rounding at L in range.
                let ck = ((x[k] / l[k]) * dims[k] as f64) as usize;
                c = c * dims[k] + ck.min(dims[k] - 1);
            }
            c as u32
        }));
        self.cell_start.clear();
        self.cell_start.resize(ncell + 1, 0);
        for &c in &self.cell_of {
            self.cell_start[c as usize + 1] += 1;
        }
        for c in 0..ncell {
            self.cell_start[c + 1] += self.cell_start[c];
        }
        let mut fill = self.cell_start.clone();
        self.members.clear();
        self.members.resize(q.len(), 0);
        for (i, &c) in self.cell_of.iter().enumerate() {
            self.members[fill[c as usize] as usize] = i as u32;
            fill[c as usize] += 1;
        }
        self.sorted.clear();
        self.sorted
            .extend(self.members.iter().map(|&i| q[i as usize]));
    }

    /// Number of cells.
    pub fn cells(&self) -> usize {
        self.dims.iter().product()
    }

    /// Whether cells of one colour own disjoint pairs (see the module docs).
    pub fn is_coloured(&self) -> bool {
        self.coloured
    }

    /// Colour of cell `c`, in `0..COLOURS` (always 0 when the grid is not coloured).
    pub fn colour(&self, c: usize) -> usize {
        if !self.coloured {
            return 0;
        }
        let (cx, cy, cz) = self.coordinates(c);
        (cx % 2) * 9 + (cy % 3) * 3 + cz % 3
    }

    /// Call `f(i, j, r2)` for every pair owned by cell `c` with squared minimum-image distance
    /// `r2 < cutoff^2` (`cutoff` at most the cell edge of the last build), in scan order,
    /// except the pairs that cross a sliding boundary (see
    /// [`CellGrid::for_each_sliding_pair_of_cell`]).
    ///
    /// Positions are read in cell order, so the inner loop reads contiguous memory; periodic
    /// images come from a per-neighbour shift instead of a minimum-image test per pair.
    pub fn for_each_pair_of_cell(
        &self,
        c: usize,
        bx: &PeriodicBox,
        shear: Option<&LeesEdwards>,
        cutoff: f64,
        mut f: impl FnMut(u32, u32, f64),
    ) {
        let cut2 = cutoff * cutoff;
        let own = self.range(c);
        if self.dims == [1, 1, 1] {
            let image = |d: Vec3| match shear {
                None => bx.min_image(d),
                Some(le) => le.min_image(bx, d).0,
            };
            for a in own.clone() {
                for b in a + 1..own.end {
                    let r2 = image(self.sorted[a] - self.sorted[b]).norm_squared();
                    if r2 < cut2 {
                        f(self.members[a], self.members[b], r2);
                    }
                }
            }
            return;
        }
        for a in own.clone() {
            for b in a + 1..own.end {
                let r2 = (self.sorted[a] - self.sorted[b]).norm_squared();
                if r2 < cut2 {
                    f(self.members[a], self.members[b], r2);
                }
            }
        }
        let sliding = is_sliding(shear);
        let [nx, ny, nz] = self.dims;
        let (cx, cy, cz) = self.coordinates(c);
        let l = bx.lengths();
        for &[dx, dy, dz] in &HALF_STENCIL {
            let (y, sy) = wrap_cell(cy, dy, ny, l.y);
            if sliding && sy != 0.0 {
                continue;
            }
            let (x, sx) = wrap_cell(cx, dx, nx, l.x);
            let (z, sz) = wrap_cell(cz, dz, nz, l.z);
            self.scan(
                &own,
                (x * ny + y) * nz + z,
                Vec3::new(sx, sy, sz),
                cut2,
                &mut f,
            );
        }
    }

    /// Call `f(i, j, r2)` for the pairs that cell `c` owns across a sliding Lees-Edwards
    /// boundary (none unless `c` is in the top row and the offset is non-zero): pairs with the
    /// images, one box up, of the bottom row's cells that overlap the x-range
    /// `[cx - 1, cx + 2)` cell widths, for `dz` in -1, 0, 1 and those cells in order of x.
    pub fn for_each_sliding_pair_of_cell(
        &self,
        c: usize,
        bx: &PeriodicBox,
        le: &LeesEdwards,
        cutoff: f64,
        mut f: impl FnMut(u32, u32, f64),
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
                self.scan(&own, k * ny * nz + z, shift, cut2, &mut f);
            }
        }
    }

    /// Call `f(i, j, r2)` once for every unordered pair with `r2 < cutoff^2`, cell by cell.
    pub fn for_each_pair(
        &self,
        bx: &PeriodicBox,
        shear: Option<&LeesEdwards>,
        cutoff: f64,
        mut f: impl FnMut(u32, u32, f64),
    ) {
        for c in 0..self.cells() {
            self.for_each_pair_of_cell(c, bx, shear, cutoff, &mut f);
            if let Some(le) = shear {
                self.for_each_sliding_pair_of_cell(c, bx, le, cutoff, &mut f);
            }
        }
    }

    /// Pairs between the particles `own` of a cell, moved by `shift`, and those of cell `other`.
    #[inline(always)]
    fn scan(
        &self,
        own: &std::ops::Range<usize>,
        other: usize,
        shift: Vec3,
        cut2: f64,
        f: &mut impl FnMut(u32, u32, f64),
    ) {
        let other = self.range(other);
        for a in own.clone() {
            let qa = self.sorted[a] + shift;
            for b in other.clone() {
                let r2 = (qa - self.sorted[b]).norm_squared();
                if r2 < cut2 {
                    f(self.members[a], self.members[b], r2);
                }
            }
        }
    }

    /// Indices into `members` / `sorted` of the particles of cell `c`.
    #[inline(always)]
    fn range(&self, c: usize) -> std::ops::Range<usize> {
        self.cell_start[c] as usize..self.cell_start[c + 1] as usize
    }

    /// `(cx, cy, cz)` of cell `c`.
    #[inline(always)]
    fn coordinates(&self, c: usize) -> (usize, usize, usize) {
        let [_, ny, nz] = self.dims;
        (c / (ny * nz), (c / nz) % ny, c % nz)
    }

    /// Whether cell `c` is in the top row (`cy = n_y - 1`) of a grid of more than one cell.
    fn is_top_row(&self, c: usize) -> bool {
        self.dims != [1, 1, 1] && self.coordinates(c).1 + 1 == self.dims[1]
    }
}

/// Whether `shear` slides the images out of alignment (non-zero offset).
#[inline(always)]
fn is_sliding(shear: Option<&LeesEdwards>) -> bool {
    shear.is_some_and(|le| le.offset() != 0.0)
}

/// The 13 neighbour offsets of a half stencil: one of each pair `{d, -d}`, all with
/// `dx` in `{0, 1}`.
const HALF_STENCIL: [[isize; 3]; 13] = [
    [1, 0, 0],
    [1, 1, 0],
    [1, -1, 0],
    [0, 1, 0],
    [1, 0, 1],
    [1, 0, -1],
    [0, 1, 1],
    [0, 1, -1],
    [1, 1, 1],
    [1, 1, -1],
    [1, -1, 1],
    [1, -1, -1],
    [0, 0, 1],
];

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

/// Pairs grouped for the sweep order: `runs[k]..runs[k + 1]` is the k-th cell's run of
/// pairs, `colours[c]..colours[c + 1]` the runs of colour `c`. When `independent` is true the
/// runs of each of the first [`COLOURS`] colours touch disjoint particles; runs of a further
/// colour (the pairs across a sliding Lees-Edwards boundary) never count as independent.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Runs {
    pub runs: Vec<u32>,
    pub colours: Vec<u32>,
    pub independent: bool,
}

/// Verlet list with a skin, in sweep order, rebuilt on displacement.
#[derive(Clone, Debug)]
pub struct VerletList {
    skin: f64,
    reference: Vec<Vec3>,
    /// The sliding boundary at the last build (its offset fixed the sweep order).
    shear: Option<LeesEdwards>,
    candidates: Vec<(u32, u32)>,
    groups: Runs,
    grid: CellGrid,
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
            candidates: Vec::new(),
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

    /// Positions of the last build (empty before the first).
    pub fn reference(&self) -> &[Vec3] {
        &self.reference
    }

    /// The sliding boundary at the last build (`None` before the first or without shear).
    pub fn reference_shear(&self) -> Option<&LeesEdwards> {
        self.shear.as_ref()
    }

    /// Rebuild if needed for positions `q` and cutoff `rc`; returns whether it rebuilt.
    pub fn update(
        &mut self,
        q: &[Vec3],
        bx: &PeriodicBox,
        shear: Option<&LeesEdwards>,
        rc: f64,
    ) -> bool {
        let rebuild = self.needs_rebuild(q, bx, shear);
        if rebuild {
            self.rebuild(q, bx, shear, rc);
        }
        rebuild
    }

    /// Build the list for positions `q`, whatever they moved.
    pub fn rebuild(&mut self, q: &[Vec3], bx: &PeriodicBox, shear: Option<&LeesEdwards>, rc: f64) {
        let reach = rc + self.skin;
        self.grid.build(q, bx, reach);
        // Cells in sweep order (colour-major), scanned on all threads, joined in order.
        let mut cells: Vec<usize> = (0..self.grid.cells()).collect();
        cells.sort_by_key(|&c| self.grid.colour(c));
        let mut per_colour = [0usize; COLOURS];
        for &c in &cells {
            per_colour[self.grid.colour(c)] += 1;
        }
        let grid = &self.grid;
        let (candidates, found) = chunked::flat_map_ordered(&cells, |&c, out| {
            grid.for_each_pair_of_cell(c, bx, shear, reach, |i, j, _| out.push((i, j)))
        });
        self.candidates = candidates;
        self.groups.runs.clear();
        self.groups.colours.clear();
        self.groups.runs.push(0);
        self.groups.colours.push(0);
        let mut found = found.into_iter();
        let mut end = 0;
        for count in per_colour {
            for n in found.by_ref().take(count) {
                end += n;
                if n > 0 {
                    self.groups.runs.push(end);
                }
            }
            self.end_colour();
        }
        if let Some(le) = shear.filter(|le| le.offset() != 0.0) {
            for c in 0..self.grid.cells() {
                if !self.grid.is_top_row(c) {
                    continue;
                }
                let found = &mut self.candidates;
                self.grid
                    .for_each_sliding_pair_of_cell(c, bx, le, reach, |i, j, _| found.push((i, j)));
                self.end_run();
            }
            self.end_colour();
        }
        self.groups.independent = self.grid.is_coloured();
        self.reference.clear();
        self.reference.extend_from_slice(q);
        self.shear = shear.copied();
        self.built = true;
        self.builds += 1;
    }

    /// Close the current cell's run, unless it is empty.
    fn end_run(&mut self) {
        let end = self.candidates.len() as u32;
        if end != *self.groups.runs.last().unwrap_or(&0) {
            self.groups.runs.push(end);
        }
    }

    /// Close the current colour.
    fn end_colour(&mut self) {
        self.groups.colours.push(self.groups.runs.len() as u32 - 1);
    }

    /// Whether [`VerletList::update`] would rebuild for positions `q`.
    pub fn needs_rebuild(&self, q: &[Vec3], bx: &PeriodicBox, shear: Option<&LeesEdwards>) -> bool {
        if !self.built || q.len() != self.reference.len() {
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

    /// Candidate pairs within `r_c + skin` at the last build, in sweep order.
    pub fn candidates(&self) -> &[(u32, u32)] {
        &self.candidates
    }

    /// Grouping of [`VerletList::candidates`] into cell runs and colours.
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

    /// The list holds exactly the brute-force pairs, and runs of one of the first `COLOURS`
    /// colours share no particle.
    fn check_list(list: &VerletList, expected: Vec<(u32, u32)>, coloured: bool, what: &str) {
        let mut got: Vec<(u32, u32)> = list
            .candidates()
            .iter()
            .map(|&(i, j)| (i.min(j), i.max(j)))
            .collect();
        got.sort_unstable();
        assert_eq!(got, expected, "{what}");
        let g = list.groups();
        assert_eq!(g.independent, coloured, "{what}");
        if g.independent {
            for c in 0..COLOURS {
                let mut seen = std::collections::HashMap::new();
                for k in g.colours[c]..g.colours[c + 1] {
                    let run = g.runs[k as usize]..g.runs[k as usize + 1];
                    for &(i, j) in &list.candidates()[run.start as usize..run.end as usize] {
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
    fn verlet_list_matches_brute_force_and_colours_are_disjoint() {
        for (l, coloured) in [(2.5, false), (4.2, false), (7.0, true), (9.5, true)] {
            let bx = PeriodicBox::new([l, l * 1.3, l * 0.9]).unwrap();
            let q = uniform_positions(&bx, 400, 1);
            let mut list = VerletList::new(0.3);
            list.update(&q, &bx, None, 1.0);
            let expected = brute(&q, 1.3, |d| bx.min_image(d));
            check_list(&list, expected, coloured, &format!("box {l}"));
            assert_eq!(list.groups().colours.len(), COLOURS + 1);
        }
    }

    #[test]
    fn sliding_list_matches_brute_force() {
        // Offsets aligned with the cells (0), slightly off, and arbitrary; grids of 3, 4 and
        // more cells along x (3 and 4 are where the four image cells wrap around).
        let boxes = [
            ([2.5, 3.25, 2.25], false),
            ([4.2, 4.5, 4.5], false),
            ([5.3, 6.9, 4.8], true),
            ([7.0, 9.1, 6.3], true),
            ([9.5, 12.35, 8.55], true),
        ];
        for (lengths, coloured) in boxes {
            let bx = PeriodicBox::new(lengths).unwrap();
            let l = lengths[0];
            let q = uniform_positions(&bx, 400, 2);
            for offset in [0.0, 1e-9, 0.37 * l, 0.999 * l] {
                let le = LeesEdwards::restore(0.3, offset, 0.0, &bx).unwrap();
                let mut list = VerletList::new(0.3);
                list.update(&q, &bx, Some(&le), 1.0);
                let expected = brute(&q, 1.3, |d| le.min_image(&bx, d).0);
                check_list(
                    &list,
                    expected,
                    coloured,
                    &format!("box {l}, offset {offset}"),
                );
                let colours = list.groups().colours.len() - 1;
                assert_eq!(colours, COLOURS + usize::from(offset != 0.0));
            }
        }
    }

    #[test]
    fn rebuilds_only_after_half_skin() {
        let bx = PeriodicBox::cubic(5.0).unwrap();
        let mut q = vec![Vec3::new(1.0, 1.0, 1.0), Vec3::new(2.0, 1.0, 1.0)];
        let mut list = VerletList::new(0.4);
        assert!(list.update(&q, &bx, None, 1.0));
        q[0].x += 0.19;
        assert!(!list.update(&q, &bx, None, 1.0));
        q[0].x += 0.02;
        assert!(list.update(&q, &bx, None, 1.0));
    }

    #[test]
    fn sliding_images_shorten_the_rebuild_interval() {
        // After the images slid by 0.1, the skin 0.4 leaves (0.4 - 0.3) / 2 = 0.05 of
        // displacement.
        let bx = PeriodicBox::cubic(5.0).unwrap();
        let mut le = LeesEdwards::new(0.1).unwrap();
        let mut q = vec![Vec3::new(1.0, 1.0, 1.0), Vec3::new(2.0, 1.0, 1.0)];
        let mut list = VerletList::new(0.4);
        assert!(list.update(&q, &bx, Some(&le), 1.0));
        le.advance(&bx, 0.2);
        q[0].x += 0.04;
        assert!(!list.update(&q, &bx, Some(&le), 1.0));
        q[0].x += 0.02;
        assert!(list.update(&q, &bx, Some(&le), 1.0));
    }
}
