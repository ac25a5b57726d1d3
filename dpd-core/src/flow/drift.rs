use crate::parallel::on_all_threads;
use crate::system::{Motion, System};
use crate::Vec3;
use rayon::prelude::*;

/// A: `q_i += h p_i / m_i`, positions wrapped into the box. Exact for any `h`.
///
/// Under Lees-Edwards boundaries the offset advances by `rate L_y h` first, and a particle
/// wrapped across the y boundary takes its image's position and x-momentum
/// ([`crate::LeesEdwards::wrap`]). With walls, frozen particles stay put and a particle
/// carried out of the channel is reflected ([`crate::walls`]).
///
/// Adds the largest single-particle displacement to the travel since the neighbour list last
/// checked the positions, which bounds the step's drift for blow-up detection, and drops
/// every position-dependent cache.
#[inline]
pub fn drift(sys: &mut System, h: f64) {
    let Motion {
        bx,
        shear,
        walls,
        q,
        p,
        inv_mass,
        mass,
    } = sys.motion();
    let particles = (q, p, inv_mass, mass);
    let max2 = match (shear, walls) {
        (None, None) => move_particles(particles, h, |q, _, _| *q = bx.wrap(*q)),
        (Some(le), _) => {
            le.advance(&bx, h);
            let le = *le;
            let kick = le.image_velocity(&bx);
            move_particles(particles, h, |q, p, m| {
                let (wrapped, n) = le.wrap(&bx, *q);
                *q = wrapped;
                p.x -= n * m * kick;
            })
        }
        (None, Some(walls)) => move_particles(particles, h, |q, p, m| {
            *q = bx.wrap(*q);
            walls.reflect(q, p, m);
        }),
    };
    sys.moved(max2.sqrt());
}

/// `q_i += h p_i / m_i`, then `wrap(q_i, p_i, m_i)` for each mobile particle (frozen ones,
/// with inverse mass 0, stay where they are); returns the largest squared displacement (NaN
/// if any is NaN). Large systems move on all threads: each particle on its own, and the
/// largest displacement does not depend on the order.
#[inline(always)]
fn move_particles(
    (q, p, inv_mass, mass): (&mut [Vec3], &mut [Vec3], &[f64], &[f64]),
    h: f64,
    wrap: impl Fn(&mut Vec3, &mut Vec3, f64) + Sync,
) -> f64 {
    #[inline(always)]
    fn moved(
        q: &mut Vec3,
        p: &mut Vec3,
        im: f64,
        m: f64,
        h: f64,
        wrap: &impl Fn(&mut Vec3, &mut Vec3, f64),
    ) -> f64 {
        if im == 0.0 {
            return 0.0;
        }
        let d = (h * im) * *p;
        *q += d;
        wrap(q, p, m);
        d.norm_squared()
    }
    // The largest squared displacement of a range of particles, NaN if any is NaN: `max`
    // skips NaN, so a NaN is caught by the sum, which only NaN makes NaN (no term is negative).
    // Neither branches (a NaN test per particle did); `moved` and `wrap` are inlined here.
    let range = |q: &mut [Vec3], p: &mut [Vec3], inv_mass: &[f64], mass: &[f64]| -> f64 {
        let (mut max2, mut sum2) = (0.0f64, 0.0);
        for (((q, p), &im), &m) in q.iter_mut().zip(p).zip(inv_mass).zip(mass) {
            let d2 = moved(q, p, im, m, h, &wrap);
            (max2, sum2) = (max2.max(d2), sum2 + d2);
        }
        if sum2.is_nan() {
            f64::NAN
        } else {
            max2
        }
    };
    // NaN is kept, so that it poisons the bound.
    let larger = |a: f64, b: f64| {
        if a.is_nan() || b.is_nan() {
            f64::NAN
        } else {
            a.max(b)
        }
    };
    if on_all_threads(q.len()) {
        q.par_chunks_mut(4096)
            .zip(p.par_chunks_mut(4096))
            .zip(inv_mass.par_chunks(4096))
            .zip(mass.par_chunks(4096))
            .map(|(((q, p), im), m)| range(q, p, im, m))
            .reduce(|| 0.0, larger)
    } else {
        range(q, p, inv_mass, mass)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::init::{cubic_box, uniform_positions};
    use crate::Params;
    use approx::assert_relative_eq;

    /// `n` particles of unit mass at rest, but particle `n / 2` with momentum `(0, 3, 4)`.
    fn system(n: usize) -> System {
        let bx = cubic_box(n, 3.0).unwrap();
        let mut p = vec![Vec3::zeros(); n];
        p[n / 2] = Vec3::new(0.0, 3.0, 4.0);
        System::builder(
            Params::builder().build().unwrap(),
            bx,
            uniform_positions(&bx, n, 5),
        )
        .momenta(p)
        .build()
        .unwrap()
    }

    /// The bound is the largest displacement, not a sum, on one thread and on two, below and
    /// above the size at which particles move on all threads (16 384); a NaN momentum makes
    /// it NaN wherever the particle is.
    #[test]
    fn the_drift_bound_is_the_largest_displacement_and_nan_poisons_it() {
        for threads in [1, 2] {
            crate::on_threads(threads, || {
                for n in [300, 40_000] {
                    let mut sys = system(n);
                    drift(&mut sys, 0.1);
                    assert_relative_eq!(sys.drift_bound(), 0.5, max_relative = 1e-15);
                    for k in [0, n / 3, n - 1] {
                        let mut sys = system(n);
                        sys.momenta_mut()[k].z = f64::NAN;
                        drift(&mut sys, 0.1);
                        assert!(sys.drift_bound().is_nan(), "n = {n}, NaN at {k}");
                    }
                }
            });
        }
    }
}
