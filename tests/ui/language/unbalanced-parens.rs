fn main() {
    let _ = dpd::dpd_scheme!("A(1/2 B O B A(1/2)");
}
