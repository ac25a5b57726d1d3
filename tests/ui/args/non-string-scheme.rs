const ABOBA: &str = "ABOBA";

fn main() {
    let _ = dpd::dpd_scheme!(ABOBA);
}
