use crate::avx2::with_avx2;
use crate::boundary::{shift_once, PeriodicBox};
use crate::parallel::on_all_threads;
use crate::system::{Motion, System};
use crate::{components, components_mut, Vec3};
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
        (None, None) => in_ranges(particles, |range| {
            // Inlined by force: a closure left to the optimiser stayed a call, compiled
            // without AVX2, and its loops were not vectorised.
            with_avx2(
                #[inline(always)]
                || move_periodic(range, h, &bx),
            )
        }),
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

/// The particles a drift moves: positions, momenta, inverse masses and masses.
type Particles<'a> = (&'a mut [Vec3], &'a mut [Vec3], &'a [f64], &'a [f64]);

/// `range(particles)` over consecutive ranges of the particles, the largest of
/// its results, NaN if any is NaN. Large systems go on all threads: each range on its own,
/// and the largest result does not depend on the order.
#[inline(always)]
fn in_ranges((q, p, inv_mass, mass): Particles, range: impl Fn(Particles) -> f64 + Sync) -> f64 {
    if on_all_threads(q.len()) {
        q.par_chunks_mut(4096)
            .zip(p.par_chunks_mut(4096))
            .zip(inv_mass.par_chunks(4096))
            .zip(mass.par_chunks(4096))
            .map(|(((q, p), im), m)| range((q, p, im, m)))
            .reduce(|| 0.0, larger)
    } else {
        range((q, p, inv_mass, mass))
    }
}

/// The larger of two largest squared displacements, NaN if either is.
#[inline(always)]
fn larger(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}

/// `q_i += h p_i / m_i`, then `wrap(q_i, p_i, m_i)` for each mobile particle (frozen ones,
/// with inverse mass 0, stay where they are); returns the largest squared displacement (NaN
/// if any is NaN).
#[inline(always)]
fn move_particles(
    particles: Particles,
    h: f64,
    wrap: impl Fn(&mut Vec3, &mut Vec3, f64) + Sync,
) -> f64 {
    in_ranges(particles, |range| move_range(range, h, &wrap))
}

/// [`move_particles`] of one range.
#[inline(always)]
fn move_range(
    (q, p, inv_mass, mass): Particles,
    h: f64,
    wrap: &impl Fn(&mut Vec3, &mut Vec3, f64),
) -> f64 {
    // `max` skips NaN, so a NaN is caught by the sum, which only NaN makes NaN (no term is
    // negative). Neither branches (a NaN test per particle did).
    let (mut max2, mut sum2) = (0.0f64, 0.0);
    for (((q, p), &im), &m) in q.iter_mut().zip(p).zip(inv_mass).zip(mass) {
        if im == 0.0 {
            continue;
        }
        let d = (h * im) * *p;
        *q += d;
        wrap(q, p, m);
        let d2 = d.norm_squared();
        (max2, sum2) = (max2.max(d2), sum2 + d2);
    }
    if sum2.is_nan() {
        f64::NAN
    } else {
        max2
    }
}

/// Particles moved at once by [`move_periodic`].
const BLOCK: usize = 64;

/// The components of a block that [`move_flat`] reads (x, y, z of each particle in turn):
/// positions, momenta, inverse masses, box lengths, all of one length.
type FlatInputs<'a> = (&'a [f64], &'a [f64], &'a [f64], &'a [f64]);

/// [`move_range`] in a periodic box, the same numbers: `BLOCK` particles at a time, over their
/// components as flat slices and without a branch, so that the compiler vectorises the work
/// (with AVX2 when called inside [`with_avx2`]; the loop over particles, with a test per
/// particle and per axis, took 57 instructions a particle, this one 34). A block in which a
/// mobile particle lands outside the box after one shift by a box length per axis (a NaN or
/// infinite position, or a move of more than a box length) is moved again, from where it was,
/// by [`move_range`] with [`PeriodicBox::wrap`].
#[inline(always)]
fn move_periodic((q, p, inv_mass, mass): Particles, h: f64, bx: &PeriodicBox) -> f64 {
    let l = bx.lengths();
    // Per component of a block: the box length and the particle's inverse mass.
    let lengths: [f64; 3 * BLOCK] = std::array::from_fn(|c| l[c % 3]);
    let mut im3 = [0.0; 3 * BLOCK];
    let (mut moved, mut squares) = ([0.0; 3 * BLOCK], [0.0; 3 * BLOCK]);
    let mut largest = 0.0f64;
    let blocks = q.chunks_mut(BLOCK).zip(p.chunks_mut(BLOCK));
    let masses = inv_mass.chunks(BLOCK).zip(mass.chunks(BLOCK));
    for ((q, p), (im, m)) in blocks.zip(masses) {
        let c = 3 * q.len();
        for (three, &im) in im3.chunks_exact_mut(3).zip(im) {
            three.fill(im);
        }
        let (moved, squares) = (&mut moved[..c], &mut squares[..c]);
        let flat = (components(q), components(p), &im3[..c], &lengths[..c]);
        let outside = move_flat(flat, h, moved, squares);
        let block = if outside {
            move_range((q, p, im, m), h, &|q, _, _| *q = bx.wrap(*q))
        } else {
            components_mut(q).copy_from_slice(moved);
            // `|d|^2` as `Vec3::norm_squared` sums it; each is +0 or above, or NaN: as bits,
            // those that are not NaN order as their values.
            let (mut bits, mut nan) = (0u64, false);
            for s in squares.chunks_exact(3) {
                let d2 = s[0] + s[1] + s[2];
                (bits, nan) = (bits.max(d2.to_bits()), nan | d2.is_nan());
            }
            if nan {
                f64::NAN
            } else {
                f64::from_bits(bits)
            }
        };
        largest = larger(largest, block);
    }
    largest
}

/// Into `moved`, the components `x + h im p` shifted once by their box length towards the box
/// ([`shift_once`]), of the mobile components (`im != 0`; the others stay as they are), and
/// into `squares` the squares of their displacements (0 for the others); whether a mobile one
/// lies outside the box after the shift.
#[inline(always)]
fn move_flat(
    (x, p, im, lengths): FlatInputs,
    h: f64,
    moved: &mut [f64],
    squares: &mut [f64],
) -> bool {
    let mut outside = 0u64;
    let inputs = x.iter().zip(p).zip(im).zip(lengths);
    for ((((&x, &p), &im), &l), (moved, square)) in inputs.zip(moved.iter_mut().zip(squares)) {
        let mobile = im != 0.0;
        let d = (h * im) * p;
        let x1 = x + d;
        let y = shift_once(x1, l);
        let inside = (y >= 0.0) & (y < l);
        outside |= u64::from(mobile & !inside);
        *moved = if mobile { y } else { x };
        *square = if mobile { d * d } else { 0.0 };
    }
    outside != 0
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

    /// The blocked periodic drift moves every particle exactly as the per-particle loop with
    /// `PeriodicBox::wrap` does, and returns the same bound: blocks full and short, frozen
    /// particles (whose NaN momentum must not count), particles that cross a face, land more
    /// than a box length out or exactly on the far face, and a NaN; with AVX2 and without.
    #[test]
    fn blocks_move_particles_as_the_particle_loop_does() {
        use rand::{Rng, SeedableRng};
        let bx = PeriodicBox::new([3.0, 4.0, 5.0]).unwrap();
        let l = bx.lengths();
        let mut rng = rand_chacha::ChaCha12Rng::seed_from_u64(3);
        for n in [1, BLOCK - 1, BLOCK, BLOCK + 1, 5 * BLOCK + 7] {
            for case in ["plain", "frozen", "far", "face", "nan"] {
                let mut q: Vec<Vec3> = (0..n)
                    .map(|_| Vec3::from_fn(|a, _| rng.random::<f64>() * l[a]))
                    .collect();
                let mut p: Vec<Vec3> = (0..n)
                    .map(|_| Vec3::from_fn(|_, _| rng.random::<f64>() * 4.0 - 2.0))
                    .collect();
                let mut inv_mass: Vec<f64> = (0..n).map(|_| rng.random_range(0.5..2.0)).collect();
                let k = rng.random_range(0..n);
                match case {
                    "frozen" => (inv_mass[k], p[k].y) = (0.0, f64::NAN),
                    "far" => p[k].x = 200.0,
                    // Lands on -1e-17, whose shift by the length rounds to the length.
                    "face" => (q[k].z, p[k].z, inv_mass[k]) = (0.0, -1e-16, 1.0),
                    "nan" => p[k].z = f64::NAN,
                    _ => {}
                }
                let mass: Vec<f64> = inv_mass.iter().map(|im| 1.0 / im).collect();
                let (mut q2, mut p2) = (q.clone(), p.clone());
                let moved = (&mut q2[..], &mut p2[..], &inv_mass[..], &mass[..]);
                let want = move_range(moved, 0.1, &|q, _, _| *q = bx.wrap(*q));
                for avx2 in [false, true] {
                    let (mut q1, mut p1) = (q.clone(), p.clone());
                    let mut run = || move_periodic((&mut q1, &mut p1, &inv_mass, &mass), 0.1, &bx);
                    let got = if avx2 { with_avx2(run) } else { run() };
                    let bits = |v: &[Vec3]| -> Vec<u64> {
                        components(v).iter().map(|x| x.to_bits()).collect()
                    };
                    let what = format!("{n} particles, {case}, AVX2 {avx2}");
                    assert_eq!(bits(&q1), bits(&q2), "positions, {what}");
                    assert_eq!(got.to_bits(), want.to_bits(), "bound, {what}");
                    assert_eq!(got.is_nan(), case == "nan", "{what}");
                }
            }
        }
    }
}
