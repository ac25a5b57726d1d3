//! A step that blows up is reported with its number and scheme, and undone.
use super::common;

use dpd_core::reference::{Aboba, VelocityVerlet};

#[test]
fn huge_dt_reports_blow_up_and_keeps_last_good_state() {
    for scheme in [&Aboba as &dyn dpd_core::Scheme, &VelocityVerlet] {
        let mut sys = common::standard_box(4.5, 5.0, 2);
        let err = common::blow_up(sys.advance(scheme, 1000));
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
        let again = common::blow_up(sys.advance(scheme, 1));
        assert_eq!(again, err);
        assert!(common::same_bits(&before, &sys));
    }
}

/// Masses and types travel with their particles through the re-sorts of list builds and
/// through the undoing of a blown-up step that re-sorted them.
#[test]
fn particle_data_follow_the_ids_through_sorts_and_undo() {
    let params = dpd_core::Params::builder()
        .a_matrix(vec![vec![25.0, 30.0], vec![30.0, 25.0]])
        .build()
        .unwrap();
    let base = dpd_core::init::equilibrium_box(params, 500, 3.0, 4)
        .unwrap()
        .build()
        .unwrap();
    let n = base.len();
    let mass = |id: u32| 0.5 + (id % 3) as f64;
    let kind = |id: u32| (id % 2) as u16;
    let mut sys = dpd_core::System::builder(
        base.params().clone(),
        *base.boundary(),
        base.positions().to_vec(),
    )
    .masses((0..n as u32).map(mass).collect())
    .kinds((0..n as u32).map(kind).collect())
    .dt(0.02)
    .build()
    .unwrap();
    let consistent = |s: &dpd_core::System| {
        s.ids()
            .iter()
            .zip(s.masses().iter().zip(s.kinds()))
            .all(|(&id, (&m, &k))| m == mass(id) && k == kind(id))
    };
    sys.advance(&Aboba, 50).unwrap();
    assert!(sys.list_builds() > 1 && consistent(&sys));
    assert_ne!(
        sys.ids(),
        &(0..n as u32).collect::<Vec<_>>()[..],
        "never re-sorted"
    );
    // The same state with a huge step: its first list build, after the drift, re-sorts the
    // scattered particles; the blown-up step is undone.
    let mut huge = dpd_core::System::builder(
        sys.params().clone(),
        *sys.boundary(),
        sys.positions().to_vec(),
    )
    .momenta(sys.momenta().to_vec())
    .masses(sys.masses().to_vec())
    .kinds(sys.kinds().to_vec())
    .ids(sys.ids().to_vec())
    .dt(50.0)
    .build()
    .unwrap();
    let before = huge.clone();
    assert!(huge.advance(&Aboba, 1).is_err());
    assert_eq!(huge.list_builds(), 1);
    assert!(consistent(&huge));
    assert!(common::same_bits(&before, &huge));
}

/// The drift bound counts how far a particle may have travelled between two checks of the
/// neighbour list, not along the whole step: one particle drifts 0.3 box edges forth and back
/// (the other particles are at rest). With a force evaluation between the two drifts the list
/// checks the positions in between and the step is good; without it the 0.6 edges add up and
/// the step is a blow-up. A skin lowers the limit from half the edge to half of (edge - skin).
#[test]
fn the_drift_bound_is_the_travel_between_checks_of_the_neighbour_list() {
    use dpd_core::flow::{drift, kick};
    use dpd_core::{System, Vec3};
    fn forth_and_back(sys: &mut System) {
        drift(sys, 1.0);
        kick(sys, 0.0);
        drift(sys, -1.0);
    }
    fn forth_then_back(sys: &mut System) {
        drift(sys, 1.0);
        drift(sys, -1.0);
    }
    // Speeds and skins in box edges.
    let moving = |speed: f64, skin: f64| common::one_moving(Vec3::new(speed, 0.0, 0.0), skin);
    let mut sys = moving(0.3, 0.0);
    sys.advance(&common::Steps("forth-and-back", forth_and_back), 1)
        .unwrap();
    let err = common::blow_up(
        moving(0.3, 0.0).advance(&common::Steps("forth-then-back", forth_then_back), 1),
    );
    assert!(
        err.reason
            .contains("between two checks of the neighbour list"),
        "{err}"
    );
    // One drift of 0.45 edges: within half the edge without a skin, beyond half of (edge -
    // 0.2 edges) with one.
    let one_drift = common::Steps("one-drift", |sys| drift(sys, 1.0));
    moving(0.45, 0.0).advance(&one_drift, 1).unwrap();
    assert!(moving(0.45, 0.2).advance(&one_drift, 1).is_err());
}
