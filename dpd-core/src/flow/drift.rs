use crate::system::System;
use crate::Vec3;

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
/// if any is NaN).
#[inline(always)]
fn move_particles(sys: &mut System, h: f64, wrap: impl Fn(&mut Vec3, &mut Vec3, f64)) -> f64 {
    let mut max2: f64 = 0.0;
    for (((q, p), &im), &m) in sys
        .q
        .iter_mut()
        .zip(&mut sys.p)
        .zip(&sys.inv_mass)
        .zip(&sys.mass)
    {
        if im == 0.0 {
            continue;
        }
        let d = (h * im) * *p;
        let d2 = d.norm_squared();
        // NaN is kept too, so that it poisons the bound.
        if d2 > max2 || d2.is_nan() {
            max2 = d2;
        }
        *q += d;
        wrap(q, p, m);
    }
    max2
}
