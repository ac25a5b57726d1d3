//! Wall-bounded flows: body-force driven Poiseuille flow has a parabolic velocity profile,
//! moving walls drive a linear (Couette) profile, fluid particles stay in the channel, and bad
//! wall set-ups are clear errors.
use super::common;

use dpd_core::init::{maxwell_momenta, uniform_positions};
use dpd_core::observe::{fit_line, Profile};
use dpd_core::reference::Aboba;
use dpd_core::{Params, PeriodicBox, System, Vec3, Walls};

/// A 5 x 5 x 10 box at density 3 with gamma = 450: walls at z = 1 and z = 9 (slabs of frozen
/// particles 1 thick on each side), moving at `velocity`, the fluid pushed by `force` along x.
fn channel(velocity: [f64; 2], force: f64, seed: u64) -> System {
    let bx = PeriodicBox::new([5.0, 5.0, 10.0]).unwrap();
    let walls = Walls::new(1.0, 9.0, velocity).unwrap();
    let q = uniform_positions(&bx, 750, seed);
    let frozen: Vec<bool> = q.iter().map(|x| !walls.contains(x.z)).collect();
    let p = maxwell_momenta(&vec![1.0; q.len()], 1.0, seed)
        .into_iter()
        .zip(&frozen)
        .map(|(p, &f)| if f { Vec3::zeros() } else { p })
        .collect();
    System::builder(Params::builder().gamma(450.0).build().unwrap(), bx, q)
        .momenta(p)
        .walls(walls)
        .frozen(frozen)
        .body_force(Vec3::new(force, 0.0, 0.0))
        .dt(0.01)
        .seed(seed)
        .build()
        .unwrap()
}

/// Run 12 time units from rest (the momentum-diffusion time across the channel,
/// `w^2 rho / (pi^2 eta)` with `eta ~ 8`, is ~2.5), then sample the x-velocity in 8 slabs of
/// the channel every 0.1 time units for 20 time units; returns `(z, u_x, weight)` per slab.
fn profile(mut sys: System) -> Vec<(f64, f64, f64)> {
    sys.advance(&Aboba, 1200).unwrap();
    let mut profile = Profile::new(&sys, 2, 10).unwrap();
    for _ in 0..200 {
        sys.advance(&Aboba, 10).unwrap();
        profile.record(&sys);
        let walls = *sys.walls().unwrap();
        let frozen = sys.frozen().unwrap();
        for (x, &f) in sys.positions().iter().zip(frozen) {
            assert!(
                f || walls.contains(x.z),
                "a fluid particle left the channel: {x:?}"
            );
        }
    }
    // Slabs 1 to 8 of 10 are the channel; 0 and 9 the walls.
    profile.rows()[1..9]
        .iter()
        .map(|r| (r.position, r.velocity[0], r.count as f64))
        .collect()
}

/// Weighted least-squares parabola `c0 + c1 z + c2 z^2`; returns the coefficients and the
/// fraction of the weighted variance it explains.
fn fit_parabola(points: &[(f64, f64, f64)]) -> ([f64; 3], f64) {
    let mut a = nalgebra::Matrix3::<f64>::zeros();
    let mut b = nalgebra::Vector3::<f64>::zeros();
    for &(z, u, w) in points {
        let basis = nalgebra::Vector3::new(1.0, z, z * z);
        a += w * basis * basis.transpose();
        b += w * u * basis;
    }
    let c = a.lu().solve(&b).unwrap();
    let total: f64 = points.iter().map(|p| p.2).sum();
    let mean = points.iter().map(|p| p.2 * p.1).sum::<f64>() / total;
    let (mut residual, mut variance) = (0.0, 0.0);
    for &(z, u, w) in points {
        residual += w * (u - (c[0] + c[1] * z + c[2] * z * z)).powi(2);
        variance += w * (u - mean).powi(2);
    }
    ([c[0], c[1], c[2]], 1.0 - residual / variance)
}

/// Shear viscosity of the fluid at gamma = 450, density 3, a = 25 (algorithms.md section 6:
/// 8.1 +- 0.2, LAMMPS `pair dpd` + `fix deform`, independent of this code).
const VISCOSITY: f64 = 8.1;
/// Channel width between the wall faces at z = 1 and z = 9, and the fluid density.
const WIDTH: f64 = 8.0;
const DENSITY: f64 = 3.0;
/// Largest slip length the tests admit at the frozen-particle walls: the no-slip plane may lie
/// up to this far inside each wall. Walls of frozen DPD particles do not stop the fluid at
/// their face; these runs put the plane 0.33 inside (Couette slope 0.231 instead of 0.250).
const MAX_SLIP: f64 = 0.45;

/// Body force g = 0.5 per particle: the profile is a parabola with its vertex in the middle of
/// the channel and peak velocity `rho g w^2 / (8 eta)` = 1.48 for no slip, up to 1.83 with
/// slip lengths up to `MAX_SLIP` (width `w + 2 slip`). The peak is the fitted parabola's
/// value at its vertex; its statistical error is ~0.01 (slab means have standard errors of
/// ~0.015, from ~75 particles and ~100 independent samples), far inside the band; a body force
/// applied twice per kick puts it at ~3.5. A parabola must explain 98 % of the variance across the slabs, and the vertex must lie
/// within 0.3 of z = 5 (its error from the slab noise is ~0.05).
#[test]
fn poiseuille_profile_is_the_parabola_of_the_viscosity() {
    let g = 0.5;
    let points = profile(channel([0.0, 0.0], g, 3));
    let ([c0, c1, c2], explained) = fit_parabola(&points);
    let vertex = -c1 / (2.0 * c2);
    let peak = c0 + c1 * vertex / 2.0;
    let no_slip = DENSITY * g * WIDTH.powi(2) / (8.0 * VISCOSITY);
    let max_peak = no_slip * (1.0 + 2.0 * MAX_SLIP / WIDTH).powi(2);
    assert!(c2 < 0.0, "{points:?}");
    assert!(explained > 0.98, "R^2 {explained}: {points:?}");
    assert!((vertex - 5.0).abs() < 0.3, "vertex {vertex}: {points:?}");
    assert!(
        peak > no_slip && peak < max_peak,
        "peak velocity {peak}, expected {no_slip} (no slip) to {max_peak}: {points:?}"
    );
}

/// Walls moving at -1 and +1 without a body force: a linear profile through 0 at the centre
/// with slope `2 U / w` = 0.25 for no slip, down to 0.225 with slip lengths up to `MAX_SLIP`
/// (about 10 % below). The slope's statistical error is ~0.003 (slab means within ~0.015 over
/// 8 slabs spread across the channel). A line explains 98 % of the variance and crosses zero
/// within 0.1 of the centre.
#[test]
fn couette_profile_is_linear_with_the_wall_speed() {
    let wall_speed = 1.0;
    let points = profile(channel([-wall_speed, wall_speed], 0.0, 5));
    let line: Vec<(f64, f64)> = points.iter().map(|p| (p.0, p.1)).collect();
    let weights: Vec<f64> = points.iter().map(|p| p.2).collect();
    let (slope, intercept) = fit_line(&line, &weights).unwrap();
    let ([_, _, c2], explained) = fit_parabola(&points);
    let no_slip = 2.0 * wall_speed / WIDTH;
    let min_slope = 2.0 * wall_speed / (WIDTH + 2.0 * MAX_SLIP);
    assert!(explained > 0.98, "R^2 {explained}: {points:?}");
    assert!(c2.abs() < 0.01, "curvature {c2}: {points:?}");
    assert!(
        slope > min_slope && slope <= no_slip,
        "slope {slope}, expected {min_slope} to {no_slip} (no slip): {points:?}"
    );
    assert!((intercept + 5.0 * slope).abs() < 0.1, "{points:?}");
}

#[test]
fn bad_wall_set_ups_are_clear_errors() {
    let bx = PeriodicBox::new([5.0, 5.0, 10.0]).unwrap();
    let walls = Walls::new(1.0, 9.0, [0.0, 0.0]).unwrap();
    let params = Params::builder().build().unwrap();
    let q = uniform_positions(&bx, 300, 1);
    // Mobile particles outside the channel.
    let err = System::builder(params.clone(), bx, q.clone())
        .walls(walls)
        .build()
        .unwrap_err();
    assert!(
        err.field.starts_with("positions[") && err.allowed.contains("channel"),
        "{err}"
    );
    // Frozen particles without walls, and walls with shear.
    let frozen: Vec<bool> = q.iter().map(|x| !walls.contains(x.z)).collect();
    let err = System::builder(params.clone(), bx, q.clone())
        .frozen(frozen.clone())
        .build()
        .unwrap_err();
    assert_eq!(err.field, "frozen");
    let err = System::builder(params.clone(), bx, q.clone())
        .walls(walls)
        .frozen(frozen)
        .shear_rate(0.1)
        .build()
        .unwrap_err();
    assert_eq!(err.field, "shear_rate");
    let err = System::builder(params, bx, q)
        .body_force(Vec3::new(f64::NAN, 0.0, 0.0))
        .build()
        .unwrap_err();
    assert_eq!(err.field, "body_force");
}

#[test]
fn wall_restart_is_bitwise_identical() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("walls.ckpt");
    let mut straight = channel([-1.0, 1.0], 0.5, 9);
    straight.advance(&Aboba, 30).unwrap();
    straight.save_checkpoint(&path, "aboba").unwrap();
    straight.advance(&Aboba, 30).unwrap();
    let (mut restarted, _) = System::load_checkpoint(&path).unwrap();
    restarted.advance(&Aboba, 30).unwrap();
    assert!(common::same_bits(&straight, &restarted));
}
