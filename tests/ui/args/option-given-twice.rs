fn main() {
    let _ = dpd::dpd_scheme!("ABOBA", name = "a", name = "b");
}
