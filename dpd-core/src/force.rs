//! Per-particle forces summed over the interacting pairs, in `(i, j)` order.

use crate::pairs::Pair;
use crate::params::Params;
use crate::rng::pair_normal;
use crate::system::System;
use crate::Vec3;

/// `out_i = F^C_i = sum_j a_ij (1 - r_ij/r_c) e_ij`.
pub(crate) fn conservative(pairs: &[Pair], params: &Params, kind: &[u16], out: &mut [Vec3]) {
    out.fill(Vec3::zeros());
    for pair in pairs {
        let (i, j) = (pair.i as usize, pair.j as usize);
        let f = params.a(kind[i], kind[j]) * pair.w * pair.e;
        out[i] += f;
        out[j] -= f;
    }
}

/// Full DPD force at the current momenta into `sys.full`:
/// `sum_j [a w - gamma w_R^2 (e . v_ij) + sigma w_R zeta_ij / sqrt(dt)] e_ij`,
/// with `zeta_ij` the pair normal of `stream` in the current step. Multiplied by a step `h`
/// this is the F kick of algorithms.md section 2.
pub(crate) fn full(sys: &mut System, stream: u8) {
    let System {
        ref pairs,
        ref p,
        ref inv_mass,
        ref kind,
        ref params,
        ref mut full,
        seed,
        step,
        dt,
        ..
    } = *sys;
    full.fill(Vec3::zeros());
    let gamma = params.gamma();
    let noise = params.sigma() / dt.sqrt();
    for pair in pairs {
        let (i, j) = (pair.i as usize, pair.j as usize);
        let u = pair.e.dot(&(p[i] * inv_mass[i] - p[j] * inv_mass[j]));
        let mut f = params.a(kind[i], kind[j]) * pair.w - gamma * pair.wr * pair.wr * u;
        if noise > 0.0 {
            f += noise * pair.wr * pair_normal(seed, step, stream, pair.i, pair.j);
        }
        let fe = f * pair.e;
        full[i] += fe;
        full[j] -= fe;
    }
}
