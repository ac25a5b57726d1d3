fn main() {
    let _ = dpd::dpd_scheme!("   ");
}
