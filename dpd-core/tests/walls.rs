//! Wall-bounded flows: body-force driven Poiseuille flow has a parabolic velocity profile,
//! moving walls drive a linear (Couette) profile, fluid particles stay in the channel, and bad
//! wall set-ups are clear errors.
mod common;

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

/// Body force 0.5 per particle: the profile is a parabola with its vertex in the middle of
/// the channel. Its amplitude, `rho g w^2 / (8 eta)` ~ 1.5, is about a hundred times the
/// standard error of a slab mean (~0.015 from ~75 particles and ~100 independent samples), so
/// a parabola must explain 98 % of the variance across the slabs, and the vertex must lie
/// within 0.3 of z = 5 (its error from the slab noise is ~0.05).
#[test]
fn poiseuille_profile_is_a_parabola() {
    let points = profile(channel([0.0, 0.0], 0.5, 3));
    let ([_, c1, c2], explained) = fit_parabola(&points);
    let vertex = -c1 / (2.0 * c2);
    assert!(c2 < 0.0, "{points:?}");
    assert!(explained > 0.98, "R^2 {explained}: {points:?}");
    assert!((vertex - 5.0).abs() < 0.3, "vertex {vertex}: {points:?}");
    let peak = points.iter().map(|p| p.1).fold(f64::MIN, f64::max);
    assert!(peak > 0.5, "{points:?}");
}

/// Walls moving at -1 and +1 without a body force: a linear profile through 0 at the centre,
/// rising towards the upper wall; a line explains 98 % of the variance and the slope lies
/// between half and all of the no-slip value 2 / 8 (slip at the walls only lowers it).
#[test]
fn couette_profile_is_linear() {
    let points = profile(channel([-1.0, 1.0], 0.0, 5));
    let line: Vec<(f64, f64)> = points.iter().map(|p| (p.0, p.1)).collect();
    let weights: Vec<f64> = points.iter().map(|p| p.2).collect();
    let (slope, intercept) = fit_line(&line, &weights).unwrap();
    let ([_, _, c2], explained) = fit_parabola(&points);
    assert!(explained > 0.98, "R^2 {explained}: {points:?}");
    assert!(c2.abs() < 0.01, "curvature {c2}: {points:?}");
    assert!(slope > 0.125 && slope < 0.25, "slope {slope}: {points:?}");
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
