fn main() {
    let _ = dpd::dpd_scheme!(
        r"
        let x = 1/(2 - 2^(1/3));
        S(x) S(1 - 2y) S(x) O
        "
    );
}
