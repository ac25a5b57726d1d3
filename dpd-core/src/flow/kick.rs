use crate::parallel::on_all_threads;
use crate::system::System;
use crate::Vec3;
use rayon::prelude::*;

/// `p_i += h f_i` for every particle, on all threads for large systems (each element on its
/// own, so the result does not depend on the thread count).
#[inline(always)]
fn add_scaled(p: &mut [Vec3], h: f64, f: &[Vec3]) {
    if on_all_threads(p.len()) {
        p.par_iter_mut()
            .zip(f)
            .with_min_len(4096)
            .for_each(|(p, f)| *p += h * f);
    } else {
        for (p, f) in p.iter_mut().zip(f) {
            *p += h * f;
        }
    }
}

/// B: `p_i += h F^C_i(q)` (plus `h g` with a body force `g`). Exact for any `h`; reuses the conservative forces while positions
/// are unchanged.
#[inline]
pub fn kick(sys: &mut System, h: f64) {
    let (p, force) = sys.momenta_and_conservative();
    add_scaled(p, h, force);
    sys.apply_body_force(h);
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
    let (p, force) = sys.momenta_and_full(stream);
    add_scaled(p, h, force);
    sys.apply_body_force(h);
    sys.record_full_kick(h);
}
