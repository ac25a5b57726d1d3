// Velocity Verlet is not a splitting of exact flows: the invariant-measure bound does not apply.
fn main() {
    let _ = dpd::dpd_scheme!("F(1/2) A F(1/2)", invariant_order >= 1);
}
