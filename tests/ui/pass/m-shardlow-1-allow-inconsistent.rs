// M-Shardlow-1 as published by Yamada et al.: x0 = +2^(1/3)/(2 - 2^(1/3)), so the coefficients
// sum to about 4.405. `allow_inconsistent` accepts it, to reproduce the published error.
use dpd::Scheme;

fn main() {
    let m1 = dpd::dpd_scheme!(
        r"
        let x0 = 2^(1/3)/(2 - 2^(1/3));
        S(x1) S(x0) S(x1) Ob
        ",
        name = "m-shardlow-1",
        allow_inconsistent,
    );
    assert_eq!(m1.name(), "m-shardlow-1");
    let analysis = m1.program().unwrap().analysis();
    assert!(!analysis.consistent);
    assert!((analysis.coefficient_sums.a - 4.405).abs() < 1e-3);
}
