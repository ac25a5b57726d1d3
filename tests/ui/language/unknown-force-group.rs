// `bonds` is not a force group (they are `pair` and `bond`); the caret marks the group.
fn main() {
    let _ = dpd::dpd_scheme!("B[pair](1/2) (B[bonds](1/8) A(1/4) B[bonds](1/8))^4 O B[pair](1/2)");
}
