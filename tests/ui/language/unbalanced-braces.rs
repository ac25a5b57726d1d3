// A brace that is never closed is refused at the brace.
fn advance(sys: &mut dpd::System) {
    let scheme = dpd::dpd_scheme!("{B(1/2) A B(1/2) O");
    sys.advance(&scheme, 10).unwrap();
}

fn main() {}
