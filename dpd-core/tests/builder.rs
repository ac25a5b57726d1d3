//! Invalid systems are rejected with the field named.
use dpd_core::{Params, PeriodicBox, System, Vec3};

fn two() -> Vec<Vec3> {
    vec![Vec3::new(0.5, 0.5, 0.5), Vec3::new(1.0, 0.5, 0.5)]
}

#[test]
fn invalid_inputs_name_their_field() {
    let params = Params::builder().build().unwrap();
    let bx = PeriodicBox::cubic(4.0).unwrap();
    let build = |f: &dyn Fn(dpd_core::SystemBuilder) -> dpd_core::SystemBuilder| {
        f(System::builder(params.clone(), bx, two()))
            .build()
            .unwrap_err()
            .field
    };
    assert_eq!(build(&|b| b.dt(0.0)), "dt");
    assert_eq!(build(&|b| b.dt(f64::NAN)), "dt");
    assert_eq!(build(&|b| b.masses(vec![1.0, -1.0])), "mass[1]");
    assert_eq!(build(&|b| b.masses(vec![1.0])), "masses");
    assert_eq!(build(&|b| b.kinds(vec![0, 3])), "kinds[1]");
    assert_eq!(build(&|b| b.skin(-0.1)), "skin");
    assert_eq!(
        build(&|b| b.momenta(vec![Vec3::zeros(), Vec3::new(f64::INFINITY, 0.0, 0.0)])),
        "momenta[1]"
    );
    let small = PeriodicBox::cubic(1.9).unwrap();
    let e = System::builder(params.clone(), small, two())
        .build()
        .unwrap_err();
    assert_eq!(e.field, "box");
    assert!(e.to_string().contains("2 (r_c + skin)"), "{e}");
    let e = System::builder(
        params,
        bx,
        vec![Vec3::new(f64::NAN, 0.0, 0.0), Vec3::zeros()],
    )
    .build()
    .unwrap_err();
    assert_eq!(e.field, "positions[0]");
}
