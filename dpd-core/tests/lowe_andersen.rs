//! Lowe-Andersen collisions (the L letter): on an ideal gas they leave the Maxwellian exactly
//! invariant, drive any start towards it, and conserve momentum to rounding; a scheme with L
//! needs a collision rate.
use super::common;

use dpd_core::init::uniform_positions;
use dpd_core::{AdvanceError, DynScheme, Params, PeriodicBox, Scheme, SweepOrder, System, Vec3};

const KBT: f64 = 1.0;

/// `n` particles of an ideal gas (a = 0, no friction) at density 3, masses alternating 1 and
/// 3, colliding at rate `rate`; every velocity component `+-sqrt(k_B T / m)` with random signs:
/// the temperature is exactly k_B T but the distribution is far from Maxwell's (kurtosis 1).
fn ideal_gas(n: usize, rate: f64, dt: f64) -> System {
    let params = Params::builder()
        .a(0.0)
        .gamma(0.0)
        .kbt(KBT)
        .collision_rate(rate)
        .build()
        .unwrap();
    let bx = PeriodicBox::cubic((n as f64 / 3.0).cbrt()).unwrap();
    let q = uniform_positions(&bx, n, 11);
    let mass = |i: usize| if i.is_multiple_of(2) { 1.0 } else { 3.0 };
    let sign = |i: usize, k: usize| match ((i * 2_654_435_761 + k * 40_503) >> 7) & 1 {
        0 => 1.0,
        _ => -1.0,
    };
    let p = (0..n)
        .map(|i| {
            let s = (KBT * mass(i)).sqrt();
            Vec3::new(sign(i, 0) * s, sign(i, 1) * s, sign(i, 2) * s)
        })
        .collect();
    System::builder(params, bx, q)
        .masses((0..n).map(mass).collect())
        .momenta(p)
        .dt(dt)
        .seed(5)
        .build()
        .unwrap()
}

/// Per mass (1, then 3): the mean of `m v^2 / k_B T` over every component, and the kurtosis
/// `<v^4> / <v^2>^2` of the components.
fn moments(sys: &System) -> [(f64, f64); 2] {
    [1.0, 3.0].map(|m| {
        let (mut s2, mut s4, mut count) = (0.0, 0.0, 0.0);
        for (p, &mi) in sys.momenta().iter().zip(sys.masses()) {
            if mi == m {
                for v in (p / m).iter() {
                    s2 += v * v;
                    s4 += v * v * v * v;
                    count += 1.0;
                }
            }
        }
        let (v2, v4) = (s2 / count, s4 / count);
        (m * v2 / KBT, v4 / (v2 * v2))
    })
}

/// The momenta by particle id (the storage order changes at neighbour-list builds).
fn by_id(sys: &System) -> Vec<Vec3> {
    let mut p = vec![Vec3::zeros(); sys.len()];
    for (&id, &pk) in sys.ids().iter().zip(sys.momenta()) {
        p[id as usize] = pk;
    }
    p
}

fn compiled(source: &str) -> DynScheme {
    DynScheme::compile(source, source, &Default::default()).unwrap()
}

#[test]
fn collisions_bring_and_keep_the_maxwellian_and_conserve_momentum() {
    // 12 000 particles, 18 000 velocity components per mass: the mean of m v^2 / k_B T has a
    // standard error of sqrt(2 / 18000) = 1.1 % and a Gaussian kurtosis of sqrt(24 / 18000) =
    // 0.037, so 5 % and 0.2 are about five standard errors. About 13 neighbours per particle
    // and p = 1 - exp(-10 * 0.05) = 0.39 per pair and step: 40 steps redraw every relative
    // velocity many times over, while a step that did not redraw from the reduced mass's
    // Maxwellian would move the temperature of one mass against the other's, and one that
    // drew no normals would leave the kurtosis away from 3 (it starts at 1).
    let mut sys = ideal_gas(12_000, 10.0, 0.05);
    let start = sys.total_momentum();
    let scale: f64 = sys.momenta().iter().map(|p| p.norm()).sum();
    for (t, kurtosis) in moments(&sys) {
        assert!((t - 1.0).abs() < 1e-12 && (kurtosis - 1.0).abs() < 1e-12);
    }
    let scheme = compiled("A(1/2) B(1/2) L B(1/2) A(1/2)");
    for _ in 0..4 {
        sys.advance(&scheme, 10).unwrap();
        for (m, (t, kurtosis)) in [1.0, 3.0].into_iter().zip(moments(&sys)) {
            assert!((t - 1.0).abs() < 0.05, "mass {m}: m v^2 / kT = {t}");
            assert!(
                (kurtosis - 3.0).abs() < 0.2,
                "mass {m}: kurtosis {kurtosis}"
            );
        }
        let drift = (sys.total_momentum() - start).norm();
        assert!(drift <= 1e-13 * scale, "momentum moved by {drift}");
    }
}

#[test]
fn collisions_happen_at_the_stated_probability() {
    // With Gamma h = ln 2 half the pairs collide. A collision leaves a pair's relative normal
    // velocity uncorrelated with the one before, a pair that does not collide keeps it; on
    // one sweep of a gas at rest but for one moving particle per pair, the pairs whose momenta
    // changed are the ones that collided (a redraw changes the momenta whatever the direction
    // of the pair). 20 000 isolated pairs: the fraction has a standard error of 0.35 %, 2 % is about
    // six.
    let pairs = 20_000;
    let (bx, q) = common::isolated_pairs(pairs);
    let p = (0..2 * pairs)
        .map(|i| match i % 2 {
            0 => Vec3::new(1.0, 0.0, 0.0),
            _ => Vec3::zeros(),
        })
        .collect();
    let dt = 0.01;
    let rate = 2f64.ln() / dt;
    let params = Params::builder().a(0.0).gamma(0.0).collision_rate(rate);
    let mut sys = System::builder(params.build().unwrap(), bx, q)
        .momenta(p)
        .dt(dt)
        .build()
        .unwrap();
    let before = by_id(&sys);
    dpd_core::flow::collide(&mut sys, dt, 0, SweepOrder::Forward);
    let after = by_id(&sys);
    let changed = (0..pairs)
        .filter(|&k| after[2 * k] != before[2 * k])
        .count();
    let fraction = changed as f64 / pairs as f64;
    assert!((fraction - 0.5).abs() < 0.02, "collided {fraction}");
}

#[test]
fn a_scheme_with_l_needs_a_collision_rate() {
    let params = Params::builder().build().unwrap();
    let bx = PeriodicBox::cubic(3.0).unwrap();
    let q = uniform_positions(&bx, 81, 1);
    let mut sys = System::builder(params, bx, q).build().unwrap();
    let scheme = compiled("B(1/2) A B(1/2) L");
    match sys.advance(&scheme, 1) {
        Err(AdvanceError::Scheme(e)) => {
            assert_eq!(e.field, "collision_rate", "{e}");
            assert!(e.to_string().contains("L (Lowe-Andersen"), "{e}");
        }
        other => panic!("expected the missing collision rate, found {other:?}"),
    }
    assert!(compiled("ABOBA").program().is_some());
}
