fn main() {
    let _ = dpd::dpd_scheme!("S(x1) S(x0) S(x1) O", order >= 20);
}
