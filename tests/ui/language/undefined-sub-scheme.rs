fn main() {
    let _ = dpd::dpd_scheme!("H(1/2) O H(1/2)");
}
