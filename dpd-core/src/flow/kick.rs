use crate::system::System;

/// B: `p_i += h F^C_i(q)` (plus `h g` with a body force `g`). Exact for any `h`; reuses the conservative forces while positions
/// are unchanged.
#[inline]
pub fn kick(sys: &mut System, h: f64) {
    sys.ensure_conservative();
    for (p, f) in sys.p.iter_mut().zip(&sys.conservative) {
        *p += h * f;
    }
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
    sys.ensure_full(stream);
    for (p, f) in sys.p.iter_mut().zip(&sys.full) {
        *p += h * f;
    }
    sys.apply_body_force(h);
    if let Some(impulses) = &mut sys.impulses {
        impulses.add_kick(h, sys.full_virial.as_ref());
    }
}
