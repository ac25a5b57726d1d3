// A user crate that depends on `dpd` only: build a small system, run a generated scheme,
// check that total momentum is conserved.
use dpd::init::{cubic_box, maxwell_momenta, uniform_positions};
use dpd::{Params, Scheme, System};

fn main() {
    let n = 100;
    let params = Params::builder().gamma(4.5).build().unwrap();
    let bx = cubic_box(n, 3.0).unwrap();
    let q = uniform_positions(&bx, n, 1);
    let p = maxwell_momenta(&vec![1.0; n], params.kbt(), 1);
    let mut sys = System::builder(params, bx, q)
        .momenta(p)
        .dt(0.02)
        .seed(1)
        .build()
        .unwrap();
    let scheme = dpd::dpd_scheme!("BAOOAB");
    assert_eq!(scheme.name(), "BAOOAB");
    let before = sys.total_momentum();
    sys.advance(&scheme, 200).unwrap();
    assert_eq!(sys.step(), 200);
    let drift = (sys.total_momentum() - before).norm();
    assert!(drift < 1e-10, "total momentum changed by {drift}");
}
