fn main() {
    let _ = dpd::dpd_scheme!("A(1/0) B O B A");
}
