//! A step that blows up is reported with its number and scheme, and undone.
mod common;

use dpd_core::reference::{Aboba, VelocityVerlet};

#[test]
fn huge_dt_reports_blow_up_and_keeps_last_good_state() {
    for scheme in [&Aboba as &dyn dpd_core::Scheme, &VelocityVerlet] {
        let mut sys = common::standard_box(4.5, 5.0, 2);
        let err = sys.advance(scheme, 1000).unwrap_err();
        assert_eq!(err.scheme, scheme.name());
        assert_eq!(err.step, sys.step(), "error names the failing step");
        assert!(err.to_string().contains("blow-up at step"));
        assert!(sys
            .positions()
            .iter()
            .chain(sys.momenta())
            .all(|v| v.iter().all(|x| x.is_finite())));
        // The kept state is the one before the failing step: retrying fails the same way.
        let before = sys.clone();
        let again = sys.advance(scheme, 1).unwrap_err();
        assert_eq!(again, err);
        assert!(common::same_bits(&before, &sys));
    }
}
