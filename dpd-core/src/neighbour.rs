//! Neighbour search in O(N): a cell grid, and a Verlet list with a skin built from it.
//!
//! The Verlet list is a half list in compressed rows: for every particle `i` the partners
//! `j > i` within `r_c + skin` at build time, in ascending order. Walking it row by row gives the
//! pairs sorted by `(i, j)`, which is the documented sweep order of the core; since pairs beyond
//! the cutoff are skipped, the order of the *interacting* pairs does not depend on when the list
//! was built. The list is rebuilt when some particle has moved more than `skin / 2` since the
//! last build.

use crate::boundary::PeriodicBox;
use crate::Vec3;

/// Particles binned into cubic-ish cells of edge at least `min_cell`.
#[derive(Clone, Debug, Default)]
pub struct CellGrid {
    dims: [usize; 3],
    /// `cell_start[c]..cell_start[c + 1]` indexes `members` for cell `c`.
    cell_start: Vec<u32>,
    members: Vec<u32>,
    cell_of: Vec<u32>,
    /// Positions gathered in cell order (scratch of `for_each_pair`).
    sorted: Vec<Vec3>,
}

impl CellGrid {
    /// Bin `q` into cells of edge >= `min_cell`. With fewer than 3 cells along some axis the
    /// grid degenerates to one cell (all pairs are then searched, which is O(N^2) but only
    /// happens for boxes smaller than three cutoffs).
    pub fn build(&mut self, q: &[Vec3], bx: &PeriodicBox, min_cell: f64) {
        let l = bx.lengths();
        let mut dims = [1usize; 3];
        for k in 0..3 {
            let n = (l[k] / min_cell).floor();
            dims[k] = if n.is_finite() && n >= 3.0 {
                (n as usize).min(1 << 10)
            } else {
                1
            };
        }
        if dims.contains(&1) {
            dims = [1, 1, 1];
        }
        self.dims = dims;
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
    }

    /// Call `f(i, j, r2)` once for every unordered pair `i != j` with squared minimum-image
    /// distance `r2 < cutoff^2`, `cutoff` at most the cell edge of the last [`CellGrid::build`].
    ///
    /// Each cell is paired with itself and with 13 of its 26 neighbours (a half stencil), and
    /// positions are first gathered in cell order, so the inner loop reads contiguous memory.
    /// Periodic images come from a per-neighbour shift instead of a minimum-image test per pair.
    pub fn for_each_pair(
        &mut self,
        q: &[Vec3],
        bx: &PeriodicBox,
        cutoff: f64,
        mut f: impl FnMut(u32, u32, f64),
    ) {
        let cut2 = cutoff * cutoff;
        if self.dims == [1, 1, 1] {
            for i in 0..q.len() {
                for j in i + 1..q.len() {
                    let r2 = bx.min_image(q[i] - q[j]).norm_squared();
                    if r2 < cut2 {
                        f(i as u32, j as u32, r2);
                    }
                }
            }
            return;
        }
        self.sorted.clear();
        self.sorted
            .extend(self.members.iter().map(|&i| q[i as usize]));
        let [nx, ny, nz] = self.dims;
        let l = bx.lengths();
        let range = |c: usize| self.cell_start[c] as usize..self.cell_start[c + 1] as usize;
        for cx in 0..nx {
            for cy in 0..ny {
                for cz in 0..nz {
                    let c = (cx * ny + cy) * nz + cz;
                    let own = range(c);
                    for a in own.clone() {
                        for b in a + 1..own.end {
                            let r2 = (self.sorted[a] - self.sorted[b]).norm_squared();
                            if r2 < cut2 {
                                f(self.members[a], self.members[b], r2);
                            }
                        }
                    }
                    for &[dx, dy, dz] in &HALF_STENCIL {
                        let (x, sx) = wrap_cell(cx, dx, nx, l.x);
                        let (y, sy) = wrap_cell(cy, dy, ny, l.y);
                        let (z, sz) = wrap_cell(cz, dz, nz, l.z);
                        let shift = Vec3::new(sx, sy, sz);
                        let other = range((x * ny + y) * nz + z);
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
                }
            }
        }
    }
}

/// The 13 neighbour offsets of a half stencil: one of each pair `{d, -d}`.
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

/// Half Verlet list with a skin, rebuilt on displacement.
#[derive(Clone, Debug)]
pub struct VerletList {
    skin: f64,
    reference: Vec<Vec3>,
    start: Vec<u32>,
    partners: Vec<u32>,
    /// Pairs found by the last build (scratch).
    found: Vec<(u32, u32)>,
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
            start: Vec::new(),
            partners: Vec::new(),
            found: Vec::new(),
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

    /// Forget the list; the next [`VerletList::update`] rebuilds it.
    pub fn invalidate(&mut self) {
        self.built = false;
    }

    /// Rebuild if needed for positions `q` and cutoff `rc`; returns whether it rebuilt.
    pub fn update(&mut self, q: &[Vec3], bx: &PeriodicBox, rc: f64) -> bool {
        if self.built && !self.moved_too_far(q, bx) {
            return false;
        }
        let reach = rc + self.skin;
        self.grid.build(q, bx, reach);
        self.found.clear();
        let found = &mut self.found;
        self.grid.for_each_pair(q, bx, reach, |i, j, _| {
            found.push(if i < j { (i, j) } else { (j, i) })
        });
        // Counting sort by i into rows, then each row by j: pairs in (i, j) order.
        self.start.clear();
        self.start.resize(q.len() + 1, 0);
        for &(i, _) in &self.found {
            self.start[i as usize + 1] += 1;
        }
        for i in 0..q.len() {
            self.start[i + 1] += self.start[i];
        }
        self.partners.clear();
        self.partners.resize(self.found.len(), 0);
        let mut fill = self.start.clone();
        for &(i, j) in &self.found {
            self.partners[fill[i as usize] as usize] = j;
            fill[i as usize] += 1;
        }
        for i in 0..q.len() {
            self.partners[self.start[i] as usize..self.start[i + 1] as usize].sort_unstable();
        }
        self.reference.clear();
        self.reference.extend_from_slice(q);
        self.built = true;
        self.builds += 1;
        true
    }

    fn moved_too_far(&self, q: &[Vec3], bx: &PeriodicBox) -> bool {
        let limit = 0.25 * self.skin * self.skin;
        q.len() != self.reference.len()
            || q.iter().zip(&self.reference).any(|(a, b)| {
                let d2 = bx.min_image(a - b).norm_squared();
                d2 > limit || d2.is_nan()
            })
    }

    /// Partners `j > i` of particle `i`, ascending.
    #[inline(always)]
    pub fn partners(&self, i: usize) -> &[u32] {
        &self.partners[self.start[i] as usize..self.start[i + 1] as usize]
    }

    /// Number of particles the list was built for.
    pub fn len(&self) -> usize {
        self.start.len().saturating_sub(1)
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    fn brute(q: &[Vec3], bx: &PeriodicBox, cut: f64) -> Vec<(u32, u32)> {
        let mut v = Vec::new();
        for i in 0..q.len() {
            for j in i + 1..q.len() {
                if bx.min_image(q[i] - q[j]).norm() < cut {
                    v.push((i as u32, j as u32));
                }
            }
        }
        v
    }

    #[test]
    fn verlet_list_matches_brute_force() {
        let mut rng = rand::rngs::StdRng::seed_from_u64(1);
        for l in [2.5, 4.2, 7.0] {
            let bx = PeriodicBox::new([l, l * 1.3, l * 0.9]).unwrap();
            let q: Vec<Vec3> = (0..300)
                .map(|_| {
                    bx.wrap(Vec3::new(
                        rng.random::<f64>() * l,
                        rng.random::<f64>() * l * 1.3,
                        rng.random::<f64>() * l * 0.9,
                    ))
                })
                .collect();
            let mut list = VerletList::new(0.3);
            list.update(&q, &bx, 1.0);
            let mut got = Vec::new();
            for i in 0..q.len() {
                got.extend(list.partners(i).iter().map(|&j| (i as u32, j)));
            }
            assert_eq!(got, brute(&q, &bx, 1.3), "box {l}");
        }
    }

    #[test]
    fn rebuilds_only_after_half_skin() {
        let bx = PeriodicBox::cubic(5.0).unwrap();
        let mut q = vec![Vec3::new(1.0, 1.0, 1.0), Vec3::new(2.0, 1.0, 1.0)];
        let mut list = VerletList::new(0.4);
        assert!(list.update(&q, &bx, 1.0));
        q[0].x += 0.19;
        assert!(!list.update(&q, &bx, 1.0));
        q[0].x += 0.02;
        assert!(list.update(&q, &bx, 1.0));
    }
}
