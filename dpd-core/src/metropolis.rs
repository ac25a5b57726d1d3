//! Samples of the configuration density `exp(-U / k_B T)` by Metropolis Monte Carlo, the
//! exact equilibrium that the KL estimator (`dpd kl`) starts its protocols from.
//!
//! A trial move displaces one particle, chosen uniformly, by a vector uniform in the cube
//! `[-d, d]^3`, and is accepted with probability `min(1, exp(-Delta U / k_B T))`: the proposal is
//! symmetric, so the chain satisfies detailed balance with respect to `exp(-U / k_B T)` and has
//! no time-step error. Consecutive states are correlated; callers space their samples by
//! sweeps (N trial moves each). `d` adapts during [`Metropolis::equilibrate`] only (adapting
//! while sampling would break detailed balance).
//!
//! Written here because the move needs the energy of one particle with its neighbours under
//! this crate's potential, box and types, a few lines on a cell list; no Monte Carlo crate
//! would save them.

use crate::boundary::PeriodicBox;
use crate::error::ParamError;
use crate::params::Params;
use crate::Vec3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha12Rng;

/// A Metropolis chain over the positions of particles with fixed types in a periodic box.
#[derive(Clone, Debug)]
pub struct Metropolis {
    params: Params,
    bx: PeriodicBox,
    kinds: Vec<u16>,
    q: Vec<Vec3>,
    cells: Cells,
    /// Half-edge `d` of the cube of trial displacements.
    max_move: f64,
    rng: ChaCha12Rng,
    tried: u64,
    accepted: u64,
}

impl Metropolis {
    /// A chain started at positions `q` (wrapped into `bx`) of particles of types `kinds`,
    /// its moves drawn from `seed`.
    pub fn new(
        params: Params,
        bx: PeriodicBox,
        q: &[Vec3],
        kinds: Vec<u16>,
        seed: u64,
    ) -> Result<Self, ParamError> {
        if kinds.len() != q.len() {
            return Err(ParamError::new(
                "kinds",
                format!("{} entries", kinds.len()),
                format!("must have one per particle ({})", q.len()),
            ));
        }
        if let Some(&k) = kinds.iter().find(|&&k| usize::from(k) >= params.types()) {
            return Err(ParamError::new(
                "kinds",
                k,
                format!("must be below the number of types, {}", params.types()),
            ));
        }
        crate::error::finite_vectors("positions", q)?;
        let q: Vec<Vec3> = q.iter().map(|&x| bx.wrap(x)).collect();
        let cells = Cells::new(&bx, params.rc(), &q);
        Ok(Metropolis {
            max_move: 0.1 * params.rc(),
            params,
            bx,
            kinds,
            q,
            cells,
            rng: ChaCha12Rng::seed_from_u64(seed),
            tried: 0,
            accepted: 0,
        })
    }

    /// Positions of the current state, in the order given.
    pub fn positions(&self) -> &[Vec3] {
        &self.q
    }

    /// Fraction of trial moves accepted since the last [`Metropolis::equilibrate`].
    pub fn acceptance(&self) -> f64 {
        self.accepted as f64 / self.tried.max(1) as f64
    }

    /// Half-edge of the cube of trial displacements.
    pub fn max_move(&self) -> f64 {
        self.max_move
    }

    /// `sweeps` sweeps that adapt the trial displacement after each sweep towards an
    /// acceptance between 0.3 and 0.5 (at most a quarter of the shortest box edge), then the
    /// counts restart. Use it before sampling.
    pub fn equilibrate(&mut self, sweeps: u64) {
        let largest = 0.25 * self.bx.min_length();
        for _ in 0..sweeps {
            self.tried = 0;
            self.accepted = 0;
            self.sweep();
            let acceptance = self.acceptance();
            if acceptance < 0.3 {
                self.max_move *= 0.9;
            } else if acceptance > 0.5 {
                self.max_move = (self.max_move * 1.1).min(largest);
            }
        }
        self.tried = 0;
        self.accepted = 0;
    }

    /// N trial moves.
    pub fn sweep(&mut self) {
        let beta = 1.0 / self.params.kbt();
        for _ in 0..self.q.len() {
            let i = self.rng.random_range(0..self.q.len());
            let d = self.max_move;
            let step = Vec3::new(
                self.rng.random_range(-d..d),
                self.rng.random_range(-d..d),
                self.rng.random_range(-d..d),
            );
            let to = self.bx.wrap(self.q[i] + step);
            let delta = self.energy_of(i, to) - self.energy_of(i, self.q[i]);
            self.tried += 1;
            // Draw only when needed: exp(-beta delta) >= 1 accepts outright.
            if delta <= 0.0 || self.rng.random::<f64>() < (-beta * delta).exp() {
                self.accepted += 1;
                self.cells.moved(i, &self.q[i], &to);
                self.q[i] = to;
            }
        }
    }

    /// The potential energy `U` of the current state.
    pub fn potential_energy(&self) -> f64 {
        0.5 * (0..self.q.len())
            .map(|i| self.energy_of(i, self.q[i]))
            .sum::<f64>()
    }

    /// The energy of particle `i` placed at `x` with every other particle.
    fn energy_of(&self, i: usize, x: Vec3) -> f64 {
        let mut u = 0.0;
        self.cells.around(&x, |j| {
            if j != i {
                let r = self.bx.min_image(x - self.q[j]).norm();
                let (ti, tj) = (self.kinds[i], self.kinds[j]);
                let rc = self.params.rc_of(ti, tj);
                if r < rc {
                    u += self.params.soft(ti, tj).energy(1.0 - r / rc);
                }
            }
        });
        u
    }
}

/// Cells of edge at least r_c; along an axis with fewer than three of them, one cell spans the
/// box (a particle's neighbours are then all particles along that axis).
#[derive(Clone, Debug)]
struct Cells {
    counts: [usize; 3],
    edge: Vec3,
    members: Vec<Vec<u32>>,
}

impl Cells {
    fn new(bx: &PeriodicBox, rc: f64, q: &[Vec3]) -> Self {
        let l = bx.lengths();
        let counts = [0, 1, 2].map(|d| match (l[d] / rc).floor() as usize {
            n if n >= 3 => n,
            _ => 1,
        });
        let edge = Vec3::new(
            l.x / counts[0] as f64,
            l.y / counts[1] as f64,
            l.z / counts[2] as f64,
        );
        let mut cells = Cells {
            counts,
            edge,
            members: vec![Vec::new(); counts.iter().product()],
        };
        for (i, x) in q.iter().enumerate() {
            let c = cells.index(cells.cell(x));
            cells.members[c].push(i as u32);
        }
        cells
    }

    /// The cell coordinates of a wrapped position.
    fn cell(&self, x: &Vec3) -> [usize; 3] {
        [0, 1, 2].map(|d| ((x[d] / self.edge[d]) as usize).min(self.counts[d] - 1))
    }

    fn index(&self, c: [usize; 3]) -> usize {
        (c[2] * self.counts[1] + c[1]) * self.counts[0] + c[0]
    }

    /// Particle `i` moved from `from` to `to`.
    fn moved(&mut self, i: usize, from: &Vec3, to: &Vec3) {
        let (a, b) = (self.index(self.cell(from)), self.index(self.cell(to)));
        if a != b {
            let cell = &mut self.members[a];
            if let Some(k) = cell.iter().position(|&j| j as usize == i) {
                cell.swap_remove(k);
            }
            self.members[b].push(i as u32);
        }
    }

    /// Call `f` with every particle in the cells around `x`'s (each once).
    fn around(&self, x: &Vec3, mut f: impl FnMut(usize)) {
        let c = self.cell(x);
        let offsets = |d: usize| -> &'static [isize] {
            if self.counts[d] >= 3 {
                &[-1, 0, 1]
            } else {
                &[0]
            }
        };
        let shifted =
            |d: usize, o: isize| (c[d] as isize + o).rem_euclid(self.counts[d] as isize) as usize;
        for &oz in offsets(2) {
            for &oy in offsets(1) {
                for &ox in offsets(0) {
                    let cell = self.index([shifted(0, ox), shifted(1, oy), shifted(2, oz)]);
                    self.members[cell].iter().for_each(|&j| f(j as usize));
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::init::{cubic_box, uniform_positions};

    /// Two particles in a cube of edge 2.5: the separation r has density proportional to
    /// r^2 exp(-phi(r) / k_B T) up to r = 1.25 (the sphere fits in the cube), so
    /// P(r < 0.7 | r < 1.2) is a ratio of one-dimensional integrals (0.1277). 400 000 sweeps
    /// give about 175 000 samples of r < 1.2, a standard error of 0.0008 for the fraction if
    /// they were independent; the tolerance 0.005 allows for their correlation. Without the
    /// Boltzmann factor the fraction would be (0.7 / 1.2)^3 = 0.198.
    #[test]
    fn two_particles_sample_the_boltzmann_density_of_their_distance() {
        let (a, kbt) = (5.0, 1.0);
        let params = Params::builder().a(a).kbt(kbt).build().unwrap();
        let bx = PeriodicBox::cubic(2.5).unwrap();
        let q = [Vec3::new(0.1, 0.2, 0.3), Vec3::new(1.4, 1.3, 1.2)];
        let mut chain = Metropolis::new(params, bx, &q, vec![0, 0], 11).unwrap();
        chain.equilibrate(1000);
        let (mut near, mut within) = (0u64, 0u64);
        for _ in 0..400_000 {
            chain.sweep();
            let x = chain.positions();
            let r = bx.min_image(x[0] - x[1]).norm();
            if r < 1.2 {
                within += 1;
                near += u64::from(r < 0.7);
            }
        }
        let weight = |r: f64| {
            let phi = if r < 1.0 {
                0.5 * a * (1.0 - r).powi(2)
            } else {
                0.0
            };
            r * r * (-phi / kbt).exp()
        };
        let integral = |hi: f64| {
            let n = 10_000;
            let h = hi / n as f64;
            (0..n)
                .map(|k| weight((k as f64 + 0.5) * h) * h)
                .sum::<f64>()
        };
        let exact = integral(0.7) / integral(1.2);
        let measured = near as f64 / within as f64;
        assert!(
            (measured - exact).abs() < 0.005,
            "measured {measured}, exact {exact}"
        );
    }

    /// The cell list finds every pair: the chain's energy equals the pair table's sum, also
    /// for a box too small for three cells along an axis.
    #[test]
    fn energy_on_cells_equals_the_pair_sum() {
        for (n, lengths) in [(400, None), (60, Some([2.5, 5.0, 4.0]))] {
            let params = Params::builder().build().unwrap();
            let bx = match lengths {
                None => cubic_box(n, 3.0).unwrap(),
                Some(l) => PeriodicBox::new(l).unwrap(),
            };
            let q = uniform_positions(&bx, n, 3);
            let mut chain = Metropolis::new(params.clone(), bx, &q, vec![0; n], 5).unwrap();
            chain.equilibrate(20);
            for _ in 0..5 {
                chain.sweep();
            }
            let mut sys = crate::System::builder(params, bx, chain.positions().to_vec())
                .build()
                .unwrap();
            let u = crate::observe::potential_energy(&mut sys);
            let rel = (chain.potential_energy() - u).abs() / u;
            assert!(
                rel < 1e-12,
                "n {n}: {} against {u}",
                chain.potential_energy()
            );
            assert!((0.2..0.6).contains(&chain.acceptance()));
        }
    }

    #[test]
    fn rejects_types_that_do_not_match() {
        let params = Params::builder().build().unwrap();
        let bx = PeriodicBox::cubic(3.0).unwrap();
        let q = vec![Vec3::zeros(); 2];
        let e = Metropolis::new(params.clone(), bx, &q, vec![0], 1).unwrap_err();
        assert_eq!(e.field, "kinds");
        let e = Metropolis::new(params, bx, &q, vec![0, 3], 1).unwrap_err();
        assert!(e.to_string().contains("number of types"), "{e}");
    }
}
