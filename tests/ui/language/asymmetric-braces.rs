// The word in braces must read the same backwards, or the accept/reject does not keep the Gibbs
// measure: the error points at the braces.
fn advance(sys: &mut dpd::System) {
    let scheme = dpd::dpd_scheme!("{B(1/3) A B(2/3)} O");
    sys.advance(&scheme, 10).unwrap();
}

fn main() {}
