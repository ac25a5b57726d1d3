// A repetition runs a whole number of times.
fn main() {
    let _ = dpd::dpd_scheme!("(B(1/4) A(1/2) B(1/4))^(5/2) O");
}
