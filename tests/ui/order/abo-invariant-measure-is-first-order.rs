fn main() {
    let _ = dpd::dpd_scheme!("ABO", invariant_order >= 2);
}
