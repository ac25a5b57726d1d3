// M-Shardlow-1 as published (the sign of x0 flipped): coefficients sum to 4.4, not 1.
fn main() {
    let _ = dpd::dpd_scheme!("S(x1) S(-x0) S(x1) Ob");
}
