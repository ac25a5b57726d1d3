fn main() {
    let _ = dpd::dpd_scheme!("ABOBA", allow_inconsistent = true);
}
