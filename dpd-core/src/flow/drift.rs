use crate::system::{on_all_threads, System};
use crate::Vec3;
use rayon::prelude::*;

/// A: `q_i += h p_i / m_i`, positions wrapped into the box. Exact for any `h`.
///
/// Under Lees-Edwards boundaries the offset advances by `rate L_y h` first, and a particle
/// wrapped across the y boundary takes its image's position and x-momentum
/// ([`crate::LeesEdwards::wrap`]). With walls, frozen particles stay put and a particle
/// carried out of the channel is reflected ([`crate::walls`]).
///
/// Adds the largest single-particle displacement to the step's drift bound used by blow-up
/// detection, and drops every position-dependent cache.
#[inline]
pub fn drift(sys: &mut System, h: f64) {
    let bx = sys.bx;
    let max2 = match (&mut sys.shear, &sys.walls) {
        (None, None) => move_particles(sys, h, |q, _, _| *q = bx.wrap(*q)),
        (Some(le), _) => {
            le.advance(&bx, h);
            let le = *le;
            let kick = le.image_velocity(&bx);
            move_particles(sys, h, |q, p, m| {
                let (wrapped, n) = le.wrap(&bx, *q);
                *q = wrapped;
                p.x -= n * m * kick;
            })
        }
        (None, Some(w)) => {
            let walls = w.walls;
            move_particles(sys, h, |q, p, m| {
                *q = bx.wrap(*q);
                walls.reflect(q, p, m);
            })
        }
    };
    sys.drift_bound += max2.sqrt();
    sys.positions_changed();
}

/// `q_i += h p_i / m_i`, then `wrap(q_i, p_i, m_i)` for each mobile particle (frozen ones,
/// with inverse mass 0, stay where they are); returns the largest squared displacement (NaN
/// if any is NaN). Large systems move on all threads: each particle on its own, and the
/// largest displacement does not depend on the order.
#[inline(always)]
fn move_particles(
    sys: &mut System,
    h: f64,
    wrap: impl Fn(&mut Vec3, &mut Vec3, f64) + Sync,
) -> f64 {
    let one = |(((q, p), &im), &m): (((&mut Vec3, &mut Vec3), &f64), &f64)| -> f64 {
        if im == 0.0 {
            return 0.0;
        }
        let d = (h * im) * *p;
        *q += d;
        wrap(q, p, m);
        d.norm_squared()
    };
    // NaN is kept, so that it poisons the bound.
    let larger = |a: f64, b: f64| {
        if a.is_nan() || b.is_nan() {
            f64::NAN
        } else {
            a.max(b)
        }
    };
    let (q, p, inv_mass, mass) = (&mut sys.q, &mut sys.p, &sys.inv_mass, &sys.mass);
    if on_all_threads(q.len()) {
        q.par_iter_mut()
            .zip(p)
            .zip(inv_mass)
            .zip(mass)
            .with_min_len(4096)
            .map(one)
            .reduce(|| 0.0, larger)
    } else {
        q.iter_mut()
            .zip(p)
            .zip(inv_mass)
            .zip(mass)
            .map(one)
            .fold(0.0, larger)
    }
}
