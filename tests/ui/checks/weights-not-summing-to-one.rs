fn main() {
    let _ = dpd::dpd_scheme!("A(1/2) B(1/2) O A(1/3)");
}
