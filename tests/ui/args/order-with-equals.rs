fn main() {
    let _ = dpd::dpd_scheme!("ABOBA", order = 2);
}
