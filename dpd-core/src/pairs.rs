//! The interacting pairs of the current positions, with the geometry every sub-flow needs.

use crate::boundary::PeriodicBox;
use crate::neighbour::VerletList;
use crate::params::Params;
use crate::Vec3;

/// One interacting pair `i < j` with `r_ij < r_c`.
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

/// Fill `out` with the interacting pairs of `q`, in `(i, j)` order.
///
/// Coincident particles (`r = 0`) have no defined direction; such a pair is left out, so it
/// exerts no force rather than a NaN one.
pub(crate) fn collect(
    list: &VerletList,
    q: &[Vec3],
    bx: &PeriodicBox,
    params: &Params,
    out: &mut Vec<Pair>,
) {
    out.clear();
    let rc = params.rc();
    let rc2 = rc * rc;
    let inv_rc = 1.0 / rc;
    for (i, &qi) in q.iter().enumerate() {
        for &j in list.partners(i) {
            let d = bx.min_image(qi - q[j as usize]);
            let r2 = d.norm_squared();
            if r2 < rc2 && r2 > 0.0 {
                let r = r2.sqrt();
                let w = 1.0 - r * inv_rc;
                out.push(Pair {
                    i: i as u32,
                    j,
                    e: d / r,
                    r,
                    w,
                    wr: params.w_r(w),
                });
            }
        }
    }
}
