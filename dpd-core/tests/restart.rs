//! A run restarted from a checkpoint continues bit for bit; bad checkpoints are clear errors.
mod common;

use dpd_core::reference::{Aboba, DpdS1, VelocityVerlet};
use dpd_core::{CheckpointError, Scheme, System};

fn check_restart<S: Scheme>(scheme: &S) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("run.ckpt");
    let mut straight = common::standard_box(4.5, 0.04, 8);
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
    check_restart(&VelocityVerlet);
    check_restart(&DpdS1);
    check_restart(&Aboba);
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
