//! Per-particle forces summed over the interacting pairs in sweep order.

use crate::pairs::{Noise, PairTable, Virial};
use crate::params::Params;
use crate::system::System;
use crate::{Tensor, Vec3};
use dpd_ir::SweepOrder;

/// `out_i = F^C_i = sum_j a_ij (1 - r_ij/r_c) e_ij`.
/// `out` is resized to one entry per particle (it is allocated on first use, so a scheme that
/// never kicks with B holds no conservative-force array).
pub(crate) fn conservative(pairs: &PairTable, params: &Params, kind: &[u16], out: &mut Vec<Vec3>) {
    out.clear();
    out.resize(kind.len(), Vec3::zeros());
    let out = pairs.write(out);
    let (kind, a) = (pairs.read(kind), params.repulsion());
    pairs.visit(SweepOrder::Forward, move |pair| {
        let f = a.of(kind.get(pair.i), kind.get(pair.j)) * pair.w * pair.e;
        // SAFETY: `visit` never hands two pairs sharing a particle to different threads, and
        // `out` was made for this table.
        unsafe {
            *out.get_paired(pair.i) += f;
            *out.get_paired(pair.j) -= f;
        }
    });
}

/// Full DPD force at the current momenta into `sys.full`:
/// `sum_j [a w - gamma w_R^2 (e . v_ij) + sigma w_R zeta_ij / sqrt(dt)] e_ij`,
/// with `zeta_ij` the pair normal of `stream` in the current step and `v_ij` including the pair's
/// velocity shift (image velocity across a sliding boundary, wall velocity of frozen particles). Multiplied by a step `h` this is the F kick of
/// algorithms.md section 2. When pair impulses are being recorded, the pair virial of the
/// dissipative and random parts goes to `sys.full_virial`.
pub(crate) fn full(sys: &mut System, stream: u8) {
    sys.full_virial = match (sys.shifted_pairs(), sys.impulses.is_some()) {
        (false, false) => {
            full_with::<false, ()>(sys, stream);
            None
        }
        (true, false) => {
            full_with::<true, ()>(sys, stream);
            None
        }
        (false, true) => Some(full_with::<false, Tensor>(sys, stream)),
        (true, true) => Some(full_with::<true, Tensor>(sys, stream)),
    };
}

#[inline(always)]
fn full_with<const SHIFTED: bool, V: Virial>(sys: &mut System, stream: u8) -> V {
    let System {
        ref mut pairs,
        ref p,
        ref inv_mass,
        ref kind,
        ref id,
        ref params,
        ref mut full,
        seed,
        step,
        dt,
        ..
    } = *sys;
    // Allocated on first use: a scheme without F holds no full-force array.
    full.clear();
    full.resize(p.len(), Vec3::zeros());
    let full = pairs.write(full);
    let (p, inv_mass, kind) = (pairs.read(p), pairs.read(inv_mass), pairs.read(kind));
    let (a, rc, gamma) = (params.repulsion(), params.rc(), params.gamma());
    let noise = params.sigma() / dt.sqrt();
    let normals = (noise > 0.0).then_some(Noise {
        seed,
        step,
        stream,
        id,
    });
    pairs.visit_sum_noisy(SweepOrder::Forward, normals, move |pair, z, dvx| {
        let (i, j) = (pair.i, pair.j);
        let u = pair.normal_velocity::<SHIFTED>(
            p.get(i) * inv_mass.get(i),
            p.get(j) * inv_mass.get(j),
            dvx,
        );
        let conservative = a.of(kind.get(i), kind.get(j)) * pair.w;
        let mut f = conservative - gamma * pair.wr * pair.wr * u;
        if noise > 0.0 {
            f += noise * pair.wr * z;
        }
        let fe = f * pair.e;
        // SAFETY: `visit` never hands two pairs sharing a particle to different threads, and
        // `full` was made for this table.
        unsafe {
            *full.get_paired(i) += fe;
            *full.get_paired(j) -= fe;
        }
        V::of(pair, rc, f - conservative)
    })
}
