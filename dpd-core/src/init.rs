//! Initial states of the standard scenes (algorithms.md section 8).

use crate::boundary::PeriodicBox;
use crate::error::{positive, ParamError};
use crate::params::Params;
use crate::system::{System, SystemBuilder};
use crate::walls::Walls;
use crate::Vec3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha12Rng;
use rand_distr::StandardNormal;

/// The generator of initial conditions: ChaCha with 12 rounds, whose output for a seed
/// rand_chacha promises not to change between versions (rand's `StdRng` makes no such
/// promise). It is the algorithm `StdRng` uses in rand 0.9, seeded the same way, so states
/// drawn before the switch are bitwise the same.
type InitRng = ChaCha12Rng;

/// The cube that holds `n` particles at number density `density`.
pub fn cubic_box(n: usize, density: f64) -> Result<PeriodicBox, ParamError> {
    let density = positive("density", density)?;
    if n == 0 {
        return Err(ParamError::new("n", n, "must be at least 1"));
    }
    PeriodicBox::cubic((n as f64 / density).cbrt())
}

/// The equilibrium box of algorithms.md section 8 for `params`: `n` unit-mass particles in the
/// cube of number density `density`, uniform positions and Maxwell momenta at `params.kbt()`
/// (total momentum removed), both drawn from `seed`, which also keys the pair random numbers.
/// Set the time step and anything else on the returned builder.
pub fn equilibrium_box(
    params: Params,
    n: usize,
    density: f64,
    seed: u64,
) -> Result<SystemBuilder, ParamError> {
    let bx = cubic_box(n, density)?;
    let q = uniform_positions(&bx, n, seed);
    let p = maxwell_momenta(&vec![1.0; n], params.kbt(), seed);
    Ok(System::builder(params, bx, q).momenta(p).seed(seed))
}

/// `n` positions drawn uniformly and independently in the box.
pub fn uniform_positions(bx: &PeriodicBox, n: usize, seed: u64) -> Vec<Vec3> {
    let mut rng = InitRng::seed_from_u64(seed);
    let l = bx.lengths();
    (0..n)
        .map(|_| {
            bx.wrap(Vec3::new(
                rng.random::<f64>() * l.x,
                rng.random::<f64>() * l.y,
                rng.random::<f64>() * l.z,
            ))
        })
        .collect()
}

/// Maxwell-Boltzmann momenta (each component normal with variance `m_i kbt`), with the total
/// momentum then removed (each particle loses its mass share), so that no centre-of-mass
/// motion biases the kinetic temperature.
pub fn maxwell_momenta(masses: &[f64], kbt: f64, seed: u64) -> Vec<Vec3> {
    let mut rng = InitRng::seed_from_u64(seed ^ 0x9E37_79B9_7F4A_7C15);
    let mut p: Vec<Vec3> = masses
        .iter()
        .map(|&m| {
            let s = (m * kbt).sqrt();
            Vec3::new(
                s * rng.sample::<f64, _>(StandardNormal),
                s * rng.sample::<f64, _>(StandardNormal),
                s * rng.sample::<f64, _>(StandardNormal),
            )
        })
        .collect();
    let total: Vec3 = p.iter().sum();
    let mass: f64 = masses.iter().sum();
    for (pi, &m) in p.iter_mut().zip(masses) {
        *pi -= (m / mass) * total;
    }
    p
}

/// The wall slabs of a channel: which particles at `q` lie outside `walls` (to be frozen, see
/// [`crate::SystemBuilder::frozen`]); their momenta in `p` are set to zero, so that the total
/// momentum is the fluid's.
pub fn freeze_outside(walls: &Walls, q: &[Vec3], p: &mut [Vec3]) -> Vec<bool> {
    q.iter()
        .zip(p)
        .map(|(x, p)| {
            let frozen = !walls.contains(x.z);
            if frozen {
                *p = Vec3::zeros();
            }
            frozen
        })
        .collect()
}
