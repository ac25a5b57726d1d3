fn main() {
    let _ = dpd::dpd_scheme!("S(x1) S(-x0) S(x1) Ob", allow_inconsistent, order >= 2);
}
