fn main() {
    let _ = dpd::dpd_scheme!("A B(1/2) O(3/2) O(-1/2) B(1/2)");
}
