// `Q` is not a sub-flow; the stub the macro leaves behind keeps `advance` free of further errors.
fn advance(sys: &mut dpd::System) {
    let scheme = dpd::dpd_scheme!("ABQBA");
    sys.advance(&scheme, 10).unwrap();
}

fn main() {}
