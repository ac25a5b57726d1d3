//! Pairs across a sliding Lees-Edwards boundary (see the module docs of [`super`]).

use super::scan::{scan, wrap_cell};
use super::CellGrid;
use crate::boundary::{LeesEdwards, PeriodicBox};
use crate::Vec3;

impl CellGrid {
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
}

/// Whether `shear` slides the images out of alignment (non-zero offset).
#[inline(always)]
pub(super) fn is_sliding(shear: Option<&LeesEdwards>) -> bool {
    shear.is_some_and(|le| le.offset() != 0.0)
}
