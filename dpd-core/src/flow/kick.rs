use crate::avx2::with_avx2;
use crate::parallel::on_all_threads;
use crate::system::System;
use crate::{components, components_mut, Vec3};
use dpd_ir::ForceGroup;
use rayon::prelude::*;

/// `p_i += h f_i` for every particle, on all threads for large systems (each element on its
/// own, so the result does not depend on the thread count). Component by component, which the
/// compiler vectorises (with AVX2 where the CPU has it): the same products and sums.
#[inline(always)]
fn add_scaled(p: &mut [Vec3], h: f64, f: &[Vec3]) {
    let parallel = on_all_threads(p.len());
    let (p, f) = (components_mut(p), components(f));
    let each = |p: &mut [f64], f: &[f64]| {
        with_avx2(
            #[inline(always)]
            || {
                for (p, f) in p.iter_mut().zip(f) {
                    *p += h * f;
                }
            },
        )
    };
    if parallel {
        p.par_chunks_mut(3 * 4096)
            .zip(f.par_chunks(3 * 4096))
            .for_each(|(p, f)| each(p, f));
    } else {
        each(p, f);
    }
}

/// B: `p_i += h F^C_i(q)`, every force: the pair forces with the body force, then the bonded
/// forces ([`kick_group`] of each group). Exact for any `h`; reuses the forces while positions
/// are unchanged.
#[inline]
pub fn kick(sys: &mut System, h: f64) {
    for group in ForceGroup::ALL {
        kick_group(sys, h, group);
    }
}

/// `B[pair]`, `B[bond]`: `p_i += h F^C_i(q)` with the forces of one group. Exact for any `h`;
/// reuses the forces while positions are unchanged.
///
/// - [`ForceGroup::Pair`]: the conservative pair forces from their cache (evaluated from the
///   pair table when stale), plus `h g` with a body force `g` (the body force is a pair-group
///   force: see [`ForceGroup::Pair`]).
/// - [`ForceGroup::Bond`]: the bonds and angles of the system's topology (see
///   [`crate::bonded`]), from their cache (evaluated when stale); nothing without a topology
///   ([`System::advance`] refuses a scheme that names `B[bond]` on a system without bonded
///   forces, [`System::check_scheme`]).
#[inline]
pub fn kick_group(sys: &mut System, h: f64, group: ForceGroup) {
    match group {
        ForceGroup::Pair => {
            let (p, force) = sys.momenta_and_conservative();
            add_scaled(p, h, force);
            sys.apply_body_force(h);
        }
        ForceGroup::Bond => {
            if let Some((p, force)) = sys.momenta_and_bonded() {
                add_scaled(p, h, force);
            }
        }
    }
}

/// F: `p_i += h F_i` with the full force (conservative + dissipative + random).
///
/// The full force is evaluated at the current momenta, with the pair normals of `stream` in the
/// current step, unless an evaluation at the current positions exists: then that one is reused
/// (velocity Verlet / Groot-Warren reuse the end-of-step forces for the next half-kick; the PRK
/// schemes give all their F stages one stream, so the noise is frozen within the step).
///
/// When pair impulses are being recorded for the stress, the kick adds `h` times the
/// dissipative and random pair virial of the evaluation it uses.
#[inline]
pub fn full_force(sys: &mut System, h: f64, stream: u8) {
    for group in ForceGroup::ALL {
        full_force_group(sys, h, stream, group);
    }
}

/// `F[pair]`: [`full_force`] with the pair forces only (conservative, dissipative and random)
/// and the body force. The bonded forces have no dissipative or random part, so their full
/// kick is their conservative kick, [`kick_group`] of [`ForceGroup::Bond`] (the scheme
/// language writes it `B[bond]` and refuses `F[bond]`).
#[inline]
pub fn full_force_group(sys: &mut System, h: f64, stream: u8, group: ForceGroup) {
    match group {
        ForceGroup::Pair => {
            let (p, force) = sys.momenta_and_full(stream);
            add_scaled(p, h, force);
            sys.apply_body_force(h);
            sys.record_full_kick(h);
        }
        ForceGroup::Bond => kick_group(sys, h, group),
    }
}
