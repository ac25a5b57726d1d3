//! Peters' thermostat (the registry's `peters`, `B A B O`): with no conservative force the pair
//! sweep alone keeps the Maxwell distribution of every velocity, and of the pairs' relative
//! normal velocities, exactly at any step, as Peters (Europhys. Lett. 66, 311 (2004)) designed
//! it; the same holds for the midpoint (BBK) update `Ob`. The explicit DPD forces of velocity
//! Verlet at a fifth of the step do not.
use super::common;

use dpd_core::init::{cubic_box, maxwell_momenta, uniform_positions};
use dpd_core::{DynScheme, Params, Scheme, System};
use dpd_schemes::lookup;

const KBT: f64 = 1.0;

/// `n` particles of an ideal gas (a = 0) at density 3 and friction `gamma`, masses
/// alternating 1 and 3, uniform positions and Maxwell momenta: the exact stationary state of
/// the thermostat alone.
fn ideal_gas(n: usize, gamma: f64, dt: f64) -> System {
    let params = Params::builder()
        .a(0.0)
        .gamma(gamma)
        .kbt(KBT)
        .build()
        .unwrap();
    let bx = cubic_box(n, 3.0).unwrap();
    let masses: Vec<f64> = (0..n).map(|i| [1.0, 3.0][i % 2]).collect();
    System::builder(params, bx, uniform_positions(&bx, n, 21))
        .momenta(maxwell_momenta(&masses, KBT, 21))
        .masses(masses)
        .dt(dt)
        .seed(21)
        .build()
        .unwrap()
}

/// Sums over the sample of `m v^2 / k_B T` per velocity component, per mass (1, then 3), and
/// of `u^2 / (k_B T (1/m_i + 1/m_j))` over the pairs within r_c (`u` the relative normal
/// velocity), each with its count.
#[derive(Default)]
struct Moments {
    per_mass: [(f64, f64); 2],
    pairs: (f64, f64),
}

impl Moments {
    fn add(&mut self, sys: &System) {
        let (q, p, m) = (sys.positions(), sys.momenta(), sys.masses());
        for (pk, &mk) in p.iter().zip(m) {
            let k = usize::from(mk != 1.0);
            self.per_mass[k].0 += pk.norm_squared() / (mk * KBT);
            self.per_mass[k].1 += 3.0;
        }
        let rc = sys.params().rc();
        for i in 0..q.len() {
            for j in i + 1..q.len() {
                let d = sys.boundary().min_image(q[i] - q[j]);
                if d.norm() < rc {
                    let u = d.normalize().dot(&(p[i] / m[i] - p[j] / m[j]));
                    self.pairs.0 += u * u / (KBT * (1.0 / m[i] + 1.0 / m[j]));
                    self.pairs.1 += 1.0;
                }
            }
        }
    }

    /// The three means: mass 1, mass 3, pairs.
    fn means(&self) -> [f64; 3] {
        let [a, b] = self.per_mass;
        [a.0 / a.1, b.0 / b.1, self.pairs.0 / self.pairs.1]
    }
}

/// The means of [`Moments`] over `samples` states `every` steps apart, after as many steps of
/// `scheme`; and the total momentum's change relative to the sum of the momenta's norms.
fn sampled(scheme: &dyn Scheme, gamma: f64, dt: f64, samples: u64, every: u64) -> ([f64; 3], f64) {
    let mut sys = ideal_gas(1500, gamma, dt);
    let p0 = sys.total_momentum();
    let mut moments = Moments::default();
    sys.advance(scheme, every).unwrap();
    for _ in 0..samples {
        sys.advance(scheme, every).unwrap();
        moments.add(&sys);
    }
    let scale: f64 = sys.momenta().iter().map(|p| p.norm()).sum();
    (moments.means(), (sys.total_momentum() - p0).norm() / scale)
}

#[test]
fn the_thermostat_alone_keeps_the_maxwellian_at_any_step() {
    // 1500 particles, 2250 components per mass, about 9400 pairs within r_c: one state's mean of
    // m v^2 / k_B T has a standard error of sqrt(2 / 2250) = 3 % per mass, the pairs' 1.5 %.
    // 20 states 4 steps apart (the sweep relaxes a pair at tau dt = gamma w_D (1/m_i + 1/m_j)
    // dt, about 0.3 on average at gamma = 4.5, dt = 0.5, and the particles move by about their
    // neighbour distance per step, so the states are nearly independent) bring them to 0.7 %
    // and 0.35 %: 3.5 % is five of the first. A sweep with the noise variance of one pair
    // wrong by its factor (1 - exp(-2 x)) -> (1 - exp(-x)) would keep that pair at
    // 1 / (1 + exp(-x)) of its k_B T, 0.57 at x = 0.3.
    let peters = lookup("peters").unwrap().scheme();
    let midpoint = DynScheme::compile("B A B Ob", "B A B Ob", &Default::default()).unwrap();
    for (gamma, dt) in [(4.5, 0.5), (200.0, 0.1)] {
        for scheme in [&*peters, &midpoint as &dyn Scheme] {
            let (means, drift) = sampled(scheme, gamma, dt, 20, 4);
            println!(
                "{} gamma {gamma} dt {dt}: {means:?}, momentum {drift:.1e}",
                scheme.name()
            );
            for (mean, what) in means.iter().zip(["mass 1", "mass 3", "pairs"]) {
                assert!(
                    (mean - 1.0).abs() < 0.035,
                    "{}, gamma {gamma}, dt {dt}, {what}: {mean}",
                    scheme.name()
                );
            }
            assert!(drift < 1e-12, "{}: momentum {drift:e}", scheme.name());
        }
    }
    // Velocity Verlet with the explicit dissipative and random forces, at gamma 4.5 and a
    // third of the step, moves the same gas off k_B T: the test tells the two apart.
    let vv = lookup("vv").unwrap().scheme();
    let (means, _) = sampled(&*vv, 4.5, 0.15, 20, 14);
    println!("vv gamma 4.5 dt 0.15: {means:?}");
    assert!(means.iter().all(|m| (m - 1.0).abs() > 0.07), "{means:?}");
}

/// The registry's `peters` is the program `B A B O`: the macro's step and the run-time
/// compiler's give the same bits.
#[test]
fn peters_is_b_a_b_o_bitwise() {
    let peters = lookup("peters").unwrap().scheme();
    let compiled = DynScheme::compile("B A B O", "B A B O", &Default::default()).unwrap();
    let (mut a, mut b) = (
        common::standard_box(&*peters, 0.04, 3),
        common::standard_box(&*peters, 0.04, 3),
    );
    a.advance(&*peters, 200).unwrap();
    b.advance(&compiled, 200).unwrap();
    assert!(common::same_state(&a, &b));
}

/// A misspelt name is refused naming it, with `peters` among the close matches; a friction
/// Peters' thermostat cannot use is refused naming `gamma`.
#[test]
fn bad_input_is_named() {
    let unknown = lookup("petres").unwrap_err();
    assert!(unknown.close_matches.contains(&"peters"), "{unknown}");
    assert!(unknown.to_string().contains("'petres'"), "{unknown}");
    for gamma in [-1.0, f64::NAN] {
        let e = Params::builder().gamma(gamma).build().unwrap_err();
        assert!(e.to_string().contains("gamma"), "{e}");
    }
}
