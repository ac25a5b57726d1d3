//! A run restarted from a checkpoint continues bit for bit; bad checkpoints are clear errors.
use super::common;

use dpd_core::reference::{Aboba, DpdS1, VelocityVerlet};
use dpd_core::{CheckpointError, Scheme, System};

/// Restarted from step 50, 50 more steps are bitwise those of the straight run (positions,
/// momenta and the storage order of the particles, which changes at every list build).
fn check_restart<S: Scheme + ?Sized>(scheme: &S, mut straight: System) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("run.ckpt");
    straight.advance(scheme, 50).unwrap();
    straight.save_checkpoint(&path, scheme.name()).unwrap();
    straight.advance(scheme, 50).unwrap();

    let (mut restarted, name) = System::load_checkpoint(&path).unwrap();
    assert_eq!(name, scheme.name());
    assert_eq!(restarted.step(), 50);
    restarted.advance(scheme, 50).unwrap();
    assert!(
        common::same_bits(&straight, &restarted),
        "{} restart diverged",
        scheme.name()
    );
}

#[test]
fn restart_is_bitwise_identical() {
    check_restart(&VelocityVerlet, common::standard_box(4.5, 0.04, 8));
    check_restart(&DpdS1, common::standard_box(4.5, 0.04, 8));
    check_restart(&Aboba, common::standard_box(4.5, 0.04, 8));
}

/// A melt of bonded chains (harmonic and FENE bonds, both angle styles) restarts bit for bit
/// too, under velocity Verlet, ABOBA and r-RESPA with the bonds on the inner step: the
/// checkpoint keeps the topology, and the bonded forces, not stored, are recomputed from the
/// positions in the same order.
#[test]
fn a_bonded_melt_restarts_bitwise() {
    let melt = || {
        common::melt(50, 6, dpd_core::Params::builder(), 9)
            .dt(0.01)
            .build()
            .unwrap()
    };
    let respa = dpd_core::DynScheme::compile(
        "respa",
        "B[pair](1/2) (B[bond](1/8) A(1/4) B[bond](1/8))^4 O B[pair](1/2)",
        &Default::default(),
    )
    .unwrap();
    check_restart(&VelocityVerlet, melt());
    check_restart(&Aboba, melt());
    check_restart(&respa, melt());
}

#[test]
fn restart_without_skin_is_bitwise_identical() {
    // Skin 0: the list keeps no reference positions and is rebuilt (and the particles
    // re-sorted) whenever they moved; a checkpoint after a step that ends with a drift (ABOBA)
    // and after one that ends with a kick on fresh forces (VV) both continue bit for bit.
    for scheme in [&VelocityVerlet as &dyn Scheme, &DpdS1, &Aboba] {
        let params = dpd_core::Params::builder().build().unwrap();
        let sys = dpd_core::init::equilibrium_box(params, 500, 3.0, 8)
            .unwrap()
            .dt(0.04)
            .skin(0.0)
            .build()
            .unwrap();
        check_restart(scheme, sys);
    }
}

#[test]
fn a_new_time_step_does_not_reuse_forces_drawn_for_the_old_one() {
    // Velocity Verlet keeps the full forces of a step's end, whose random part is scaled by
    // dt, for the next step's first half-kick. After `set_dt` the next steps must be those of
    // a system whose caches were dropped by a change of positions (skin 0: the list is rebuilt
    // at every change anyway, so the pair order is the same), not those reusing the old noise.
    let params = dpd_core::Params::builder().build().unwrap();
    let mut a = dpd_core::init::equilibrium_box(params, 500, 3.0, 8)
        .unwrap()
        .dt(0.04)
        .skin(0.0)
        .build()
        .unwrap();
    a.advance(&VelocityVerlet, 50).unwrap();
    let mut b = a.clone();
    let q = b.positions().to_vec();
    b.set_positions(&q).unwrap();
    a.set_dt(0.02).unwrap();
    b.set_dt(0.02).unwrap();
    for s in [&mut a, &mut b] {
        s.advance(&VelocityVerlet, 50).unwrap();
    }
    assert!(
        common::same_bits(&a, &b),
        "set_dt kept forces of the old dt"
    );
    assert!(a.set_dt(0.0).unwrap_err().to_string().contains("dt"));
    assert!(a.set_dt(f64::NAN).is_err());
}

#[test]
fn damaged_checkpoints_are_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("run.ckpt");
    let sys = common::standard_box(4.5, 0.04, 8);
    sys.save_checkpoint(&path, "aboba").unwrap();
    let good = std::fs::read(&path).unwrap();

    std::fs::write(&path, &good[..good.len() / 2]).unwrap();
    assert!(matches!(
        System::load_checkpoint(&path),
        Err(CheckpointError::Truncated { .. })
    ));

    let mut flipped = good.clone();
    let k = flipped.len() - 100;
    flipped[k] ^= 0x10;
    std::fs::write(&path, &flipped).unwrap();
    let err = System::load_checkpoint(&path).unwrap_err();
    assert!(matches!(err, CheckpointError::Corrupt { .. }), "{err}");
    assert!(err.to_string().contains("checksum"));

    std::fs::write(&path, b"hello world, not a checkpoint at all").unwrap();
    assert!(matches!(
        System::load_checkpoint(&path),
        Err(CheckpointError::NotACheckpoint { .. })
    ));

    let missing = dir.path().join("missing.ckpt");
    assert!(matches!(
        System::load_checkpoint(&missing),
        Err(CheckpointError::Io { .. })
    ));
}

#[test]
fn overwriting_keeps_a_readable_checkpoint() {
    // The write goes through a temporary file and a rename: the target is always either the
    // old or the new complete checkpoint, and no temporary file is left behind.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("run.ckpt");
    let mut sys = common::standard_box(4.5, 0.04, 8);
    sys.save_checkpoint(&path, "aboba").unwrap();
    sys.advance(&Aboba, 3).unwrap();
    sys.save_checkpoint(&path, "aboba").unwrap();
    assert_eq!(System::load_checkpoint(&path).unwrap().0.step(), 3);
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

/// The blow-up guard's travel since the last check of the neighbour list carries across
/// steps, and across a checkpoint: a scheme that only drifts (no force, so the list never
/// checks) moves one particle 0.3 box edges per step, and its second step is a blow-up
/// whether or not the run was restarted in between.
#[test]
fn restart_keeps_the_travel_of_the_blow_up_guard() {
    use dpd_core::flow::drift;
    use dpd_core::Vec3;
    let mut sys = common::one_moving(Vec3::new(0.0, 0.3, 0.0), 0.0);
    let only_drift = common::Steps("only-drift", |sys| drift(sys, 1.0));
    sys.advance(&only_drift, 1).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("run.ckpt");
    sys.save_checkpoint(&path, "only-drift").unwrap();
    let straight = sys.advance(&only_drift, 1).unwrap_err();
    let (mut restarted, _) = System::load_checkpoint(&path).unwrap();
    assert_eq!(restarted.advance(&only_drift, 1).unwrap_err(), straight);
}
