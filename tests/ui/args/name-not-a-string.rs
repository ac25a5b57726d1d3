fn main() {
    let _ = dpd::dpd_scheme!("ABOBA", name = aboba);
}
