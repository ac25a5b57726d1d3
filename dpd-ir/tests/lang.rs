//! The scheme language end to end: examples, merged sequences, costs, errors, robustness.

use dpd_ir::lang::{compile, compile_with, Diagnostic, Options};
use dpd_ir::program::Program;
use dpd_ir::{Flow, SweepOrder};
use num_rational::BigRational;
use proptest::prelude::*;

fn ok(src: &str) -> Program {
    compile(src).unwrap_or_else(|e| panic!("{src}: {e:?}"))
}

fn lenient(src: &str) -> Program {
    let options = Options {
        allow_inconsistent: true,
    };
    compile_with(src, &options).unwrap_or_else(|e| panic!("{src}: {e:?}"))
}

fn err(src: &str) -> Vec<Diagnostic> {
    match compile(src) {
        Ok(p) => panic!("{src} compiled to {p}"),
        Err(e) => e,
    }
}

/// The single error of `src`, which must contain `needle`; returns its span text.
fn one_err<'a>(src: &'a str, needle: &str) -> &'a str {
    let e = err(src);
    assert_eq!(e.len(), 1, "{src}: {e:?}");
    assert!(e[0].message.contains(needle), "{src}: {}", e[0].message);
    &src[e[0].span.clone()]
}

fn ratio(n: i64, d: i64) -> BigRational {
    BigRational::new(n.into(), d.into())
}

#[test]
fn merged_sequences_of_the_named_schemes() {
    for (src, merged) in [
        ("ABOBA", "A(1/2) B(1/2) O(1) B(1/2) A(1/2)"),
        (
            "A(1/2) B(1/2) O B(1/2) A(1/2)",
            "A(1/2) B(1/2) O(1) B(1/2) A(1/2)",
        ),
        ("OBAB", "O(1) B(1/2) A(1) B(1/2)"),
        ("ObBAB", "Ob(1) B(1/2) A(1) B(1/2)"),
        ("BAOOAB", "B(1/2) A(1/2) O(1/2) O(1/2) A(1/2) B(1/2)"),
        ("OBABO", "O(1/2) B(1/2) A(1) B(1/2) O(1/2)"),
        (
            "Ob(1/2) B A B Ob(1/2)",
            "Ob(1/2) B(1/2) A(1) B(1/2) Ob(1/2)",
        ),
        ("TAT", "T(1/2) A(1) T(1/2)"),
        ("A T A", "A(1/2) T(1) A(1/2)"),
        ("F(1/2) A F(1/2)", "F(1/2) A(1) F(1/2)"),
        ("BAOAB", "B(1/2) A(1/2) O(1) A(1/2) B(1/2)"),
        (" A\tB\nO B A ", "A(1/2) B(1/2) O(1) B(1/2) A(1/2)"),
    ] {
        assert_eq!(ok(src).to_string(), merged, "{src}");
    }
}

#[test]
fn implicit_occurrences_share_the_remainder() {
    let p = ok("A(1/4) B A A O");
    let a: Vec<_> = p
        .unmerged_stages
        .iter()
        .filter(|s| s.flow == Flow::A)
        .collect();
    assert_eq!(a[1].coeff.exact, Some(ratio(3, 8)));
    assert_eq!(a[2].coeff.exact, Some(ratio(3, 8)));
    assert_eq!(p.to_string(), "A(1/4) B(1) A(3/4) O(1)");
}

#[test]
fn adjacent_drifts_and_kicks_merge_and_zeros_vanish() {
    let p = ok("A A B B O");
    assert_eq!(p.to_string(), "A(1) B(1) O(1)");
    assert_eq!(p.unmerged_stages.len(), 5);
    assert_eq!(ok("A(1/2) B(0) A(1/2) B O").to_string(), "A(1) B(1) O(1)");
    assert_eq!(ok("F(1/2) F(1/2) A").to_string(), "F(1) A(1)");
    // A cancelled drift lets the kicks around it merge.
    let p = lenient("B(1/2) A(1) A(-1) B(1/2) A O");
    assert_eq!(p.to_string(), "B(1) A(1) O(1)");
    // Sweeps never merge.
    assert_eq!(ok("AB O(1/2) O(1/2)").stages.len(), 4);
}

#[test]
fn evaluation_costs_in_the_steady_state() {
    for (src, force, distance) in [
        ("ABOBA", 1, 1),
        ("OBAB", 1, 1),
        ("ObBAB", 1, 1),
        ("F(1/2) A F(1/2)", 1, 1),
        ("BAOAB", 1, 2),
        ("BAOOAB", 1, 2),
        ("TAT", 2, 1),
        ("ATA", 1, 1),
        (
            "prk(b = [7/24, 3/4, -1/24], bh = [2/3, -2/3, 1], kick = F)",
            3,
            3,
        ),
        ("S(x1) S(x0) S(x1) Ob", 3, 3),
    ] {
        let p = ok(src);
        assert_eq!(p.force_evaluations_per_step(), force, "{src}");
        assert_eq!(p.pair_distance_evaluations_per_step(), distance, "{src}");
    }
}

#[test]
fn symmetry() {
    for src in [
        "ABOBA",
        "BAOOAB",
        "OBABO",
        "TAT",
        "BAOAB",
        "F(1/2) A F(1/2)",
        "S(x1)S(x0)S(x1)",
    ] {
        assert!(ok(src).is_symmetric(), "{src}");
    }
    for src in ["OBAB", "BAO>O>AB", "ABO", "S(x1)S(x0)S(x1) O"] {
        assert!(!ok(src).is_symmetric(), "{src}");
    }
    // A single central sweep is its own mirror, in either order.
    assert!(ok("ABO<BA").is_symmetric());
}

#[test]
fn sweep_orders_alternate_unless_forced() {
    let orders = |src: &str| -> Vec<SweepOrder> {
        ok(src)
            .stages
            .iter()
            .filter(|s| s.flow.is_successive_sweep())
            .map(|s| s.order)
            .collect()
    };
    use SweepOrder::{Forward as F, Reverse as R};
    assert_eq!(orders("BAOOAB"), [F, R]);
    assert_eq!(orders("Ob(1/2) BAB Ob(1/2)"), [F, R]);
    assert_eq!(orders("AB O(1/3) O(1/3) O(1/3)"), [F, R, F]);
    assert_eq!(orders("BAO<O>AB"), [R, F]);
    assert_eq!(orders("T>(1/2) A T>(1/2)"), [F, F]);
    // The printed form marks only departures from the default, and compiles back.
    let p = ok("BAO>O>AB");
    assert_eq!(p.to_string(), "B(1/2) A(1/2) O(1/2) O>(1/2) A(1/2) B(1/2)");
    assert_eq!(ok(&p.to_string()).stages, p.stages);
    assert_eq!(
        format!("{p:#}"),
        "B(1/2) A(1/2) O>(1/2)@0 O>(1/2)@1 A(1/2) B(1/2)"
    );
}

#[test]
fn streams() {
    let streams = |p: &Program| p.stages.iter().map(|s| s.stream).collect::<Vec<_>>();
    assert_eq!(streams(&ok("BAOOAB")), [0, 0, 0, 1, 0, 0]);
    assert_eq!(streams(&ok("F(1/2) A F(1/2)")), [0, 0, 1]);
    assert_eq!(streams(&ok("T A T")), [0, 0, 1]);
    let prk = "prk(b = [7/24, 3/4, -1/24], bh = [2/3, -2/3, 1], kick = F)";
    assert_eq!(streams(&ok(prk)), [0, 0, 0, 0, 0, 0]);
    // Two frozen-noise tables with half steps: one stream each.
    let two = "prk(b = [7/48, 3/8, -1/48], bh = [1/3, -1/3, 1/2]) prk(b = [7/48, 3/8, -1/48], bh = [1/3, -1/3, 1/2])";
    assert_eq!(streams(&ok(two)), [0, 0, 0, 0, 0, 0, 1, 0, 1, 0, 1, 0]);
}

#[test]
fn exact_and_float_coefficients() {
    let p = ok("A(sqrt(9/4) - 1) A(2^-1) B(0.5) B(1/2) O(cbrt(-8) + 3)");
    assert_eq!(p.to_string(), "A(1) B(1) O(1)");
    let p = lenient("A(sqrt(2)) B O");
    assert_eq!(p.stages[0].coeff.exact, None);
    assert_eq!(p.stages[0].coeff.value, 2f64.sqrt());
    // Implicit multiplication and precedence.
    assert_eq!(
        ok("A(1-2(1/4)) A(-2^-1 + 1) B O").to_string(),
        "A(1) B(1) O(1)"
    );
    // Irrational sums are checked with a tolerance.
    ok("A(sqrt(2)) A(1 - sqrt(2)) B O");
}

#[test]
fn yoshida_triple_jump_and_m_shardlow() {
    let p = ok("S(x1) S(x0) S(x1)");
    let x1 = 1.0 / (2.0 - 2f64.powf(1.0 / 3.0));
    let x0 = -(2f64.powf(1.0 / 3.0)) * x1;
    let a: Vec<f64> = p
        .stages
        .iter()
        .filter(|s| s.flow == Flow::A)
        .map(|s| s.coeff.value)
        .collect();
    assert_eq!(a.len(), 3);
    approx::assert_relative_eq!(a[0], x1, max_relative = 1e-15);
    approx::assert_relative_eq!(a[1], x0, max_relative = 1e-15);
    approx::assert_relative_eq!(a[2], x1, max_relative = 1e-15);
    // The compiled value is the same every time (it is baked into code by the macro).
    assert_eq!(ok("S(x1) S(x0) S(x1)").stages, p.stages);
    // The same with user-written constants and base.
    let own = ok("let y = 1/(2 - 2^(1/3)); def H(c) = B(c/2) A(c) B(c/2); H(y) H(1-2y) H(y)");
    for (s, t) in own.stages.iter().zip(&p.stages) {
        approx::assert_relative_eq!(s.coeff.value, t.coeff.value, max_relative = 1e-14);
    }
    // M-Shardlow-2 is consistent; M-Shardlow-1 (x0 with the published + sign) is not.
    ok("S(x1)S(x0)S(x1) Ob");
    let m1 = "let xp = 2^(1/3)/(2 - 2^(1/3)); S(x1) S(xp) S(x1) Ob";
    let e = err(m1);
    assert_eq!(e.len(), 2, "{e:?}");
    for d in &e {
        assert!(d.message.contains("sum to 4.4048"), "{}", d.message);
    }
    assert!(e[0].message.contains("the A coefficients"));
    assert!(e[1].message.contains("the B coefficients"));
    assert_eq!(lenient(m1).force_evaluations_per_step(), 3);
    // A user-defined base step replaces the default one.
    let p = ok("def S(c) = A(c/2) B(c) A(c/2); S(x1) S(x0) S(x1) O");
    assert_eq!(p.stages[0].flow, Flow::A);
    assert_eq!(p.force_evaluations_per_step(), 3);
}

/// The third-order PRK tables of algorithms.md section 3.
const PRK_TABLES: [(&str, &str, &str); 3] = [
    ("Ruth", "7/24, 3/4, -1/24", "2/3, -2/3, 1"),
    (
        "Iwatsu A",
        "(-7 + sqrt(209/2))/12, 11/12, (8 - sqrt(209/2))/12",
        "(2/9)(1 + sqrt(38/11)), (2/9)(1 - sqrt(38/11)), 5/9",
    ),
    (
        "Iwatsu B",
        "-(7 + sqrt(209/2))/12, 11/12, (8 + sqrt(209/2))/12",
        "(2/9)(1 - sqrt(38/11)), (2/9)(1 + sqrt(38/11)), 5/9",
    ),
];

#[test]
fn prk_tables_satisfy_the_published_order_conditions() {
    for (name, b, bh) in PRK_TABLES {
        let p = ok(&format!("prk(b = [{b}], bh = [{bh}], kick = F)"));
        assert_eq!(p.stages.len(), 6, "{name}");
        let c: Vec<f64> = p.stages.iter().map(|s| s.coeff.value).collect();
        let (b1, bh1, b2, bh2, b3, bh3) = (c[0], c[1], c[2], c[3], c[4], c[5]);
        let tol = 1e-13;
        assert!((b1 + b2 + b3 - 1.0).abs() < tol, "{name} (12)");
        assert!(
            (b2 * bh1 + b3 * (bh1 + bh2) - 0.5).abs() < tol,
            "{name} (13)"
        );
        assert!(
            (b2 * bh1 * bh1 + b3 * (bh1 + bh2).powi(2) - 1.0 / 3.0).abs() < tol,
            "{name} (14)"
        );
        assert!((bh1 + bh2 + bh3 - 1.0).abs() < tol, "{name} (15)");
        let s16 = bh1 * b1 * b1 + bh2 * (b1 + b2).powi(2) + bh3 * (b1 + b2 + b3).powi(2);
        assert!((s16 - 1.0 / 3.0).abs() < tol, "{name} (16)");
        assert!(p.stages.iter().all(|s| s.stream == 0), "{name}");
        // The Hamiltonian form composes with a sweep.
        let h = ok(&format!("prk(b = [{b}], bh = [{bh}], kick = B) O"));
        assert_eq!(h.stages.len(), 7, "{name}");
        assert_eq!(h.stages[6].flow, Flow::O);
        assert!(h.stages[..6].iter().all(|s| s.flow != Flow::F));
    }
    let ruth = ok("prk(b = [7/24, 3/4, -1/24], bh = [2/3, -2/3, 1], kick = F)");
    assert_eq!(
        ruth.to_string(),
        "F(7/24) A(2/3) F(3/4) A(-2/3) F(-1/24) A(1)"
    );
    assert_eq!(ruth.stages[0].coeff.exact, Some(ratio(7, 24)));
}

#[test]
fn sub_schemes_nest() {
    let p = ok("def H(c) = S(c/2) S(c/2); def G = H(1/2); G H(1/2) O");
    assert_eq!(
        p.to_string(),
        "B(1/8) A(1/4) B(1/4) A(1/4) B(1/4) A(1/4) B(1/4) A(1/4) B(1/8) O(1)"
    );
    ok("def K = B A B; K O");
    let p = ok("let h = 1/2; let q = h/2; A(q) A(q) B(h) O B(h) A(h)");
    assert_eq!(p.to_string(), "A(1/2) B(1/2) O(1) B(1/2) A(1/2)");
}

#[test]
fn program_serializes() {
    let json = serde_json::to_value(ok("ABOBA")).unwrap();
    assert_eq!(json["source"], "ABOBA");
    assert_eq!(json["stages"].as_array().map(Vec::len), Some(5));
    assert_eq!(json["stages"][2]["flow"], "O");
    assert_eq!(json["stages"][2]["coeff"]["value"], 1.0);
}

#[test]
fn errors_point_at_their_source() {
    assert_eq!(err("")[0].span, 0..0);
    assert!(err(" \n ")[0].message.contains("empty scheme"));
    assert_eq!(
        err("ABQ")[0].message,
        "unknown sub-flow 'Q' at position 3; expected one of A, B, O, Ob, T, F, L, Oa, On, Xi, S or a defined name"
    );
    assert_eq!(one_err("ABQ", "unknown sub-flow"), "Q");
    assert_eq!(one_err("AB x", "unknown sub-flow 'x'"), "x");
    assert_eq!(err("ABQ O Z").len(), 2);
    assert_eq!(one_err("A(1/2 B O", "never closed"), "(");
    assert_eq!(one_err("A)B O", "no matching"), ")");
    assert_eq!(one_err("A(1/2] B O", "does not match"), "]");
    assert_eq!(one_err("A(y) B O", "undefined constant 'y'"), "y");
    assert_eq!(one_err("A B O H(1)", "unknown sub-flow 'H'"), "H");
    assert_eq!(
        one_err("A(1, 2) B O", "wrong number of arguments"),
        "A(1, 2)"
    );
    assert_eq!(
        one_err("A B(1) S(1, 2) O", "S(c) takes 1, found 2"),
        "S(1, 2)"
    );
    assert_eq!(one_err("A B(1/0) O", "division by zero"), "1/0");
    assert_eq!(one_err("A B(10^10^10) O", "power too large"), "10^10^10");
    assert_eq!(one_err("A B(2^sqrt(2)) O", "exponent"), "2^sqrt(2)");
    assert_eq!(one_err("A B(sqrt(-1)) O", "even root"), "sqrt(-1)");
    assert_eq!(one_err("B O", "no drift"), "B O");
    assert_eq!(one_err("A O", "no conservative force"), "A O");
    let options = Options {
        allow_inconsistent: true,
    };
    let e = compile_with("A B O(-1/2)", &options).unwrap_err();
    assert_eq!((e.len(), &e[0].span), (1, &(4..11)), "{e:?}");
    assert!(e[0].message.contains("cannot run backwards"));
    let e = compile_with("A B O(0) Ob(1) T(0)", &options).unwrap_err();
    assert_eq!(e.len(), 2, "{e:?}");
    let e = compile_with("A B L(-1)", &options).unwrap_err();
    assert!(e[0].message.contains("L is a stochastic sweep"), "{e:?}");
    // Lowe-Andersen collisions thermostat alone; the error points at the first L.
    assert_eq!(
        one_err("O(1/2) B A B L(1/2)", "cannot be combined"),
        "L(1/2)"
    );
    let lowe = ok("B A B L");
    assert_eq!(lowe.stages[3].flow, Flow::L);
    assert_eq!(lowe.to_string(), "B(1/2) A(1) B(1/2) L(1)");
    // The adaptive thermostat: Oa and Xi together, alone, the Xi steps summing to one.
    let padl = ok("B A Xi(1/2) Oa Xi(1/2) A B");
    assert_eq!(
        padl.stages.iter().map(|s| s.flow).collect::<Vec<_>>(),
        [
            Flow::B,
            Flow::A,
            Flow::Xi,
            Flow::Oa,
            Flow::Xi,
            Flow::A,
            Flow::B
        ]
    );
    assert_eq!(one_err("BAOaAB", "Oa needs an Xi stage"), "Oa");
    assert_eq!(one_err("BAOAB Xi", "Xi needs an Oa or On stage"), "Xi");
    // The pairwise Nose-Hoover-Langevin thermostat: On with Xi, alone.
    let pnhl = ok("B A Xi(1/2) On Xi(1/2) A B");
    assert_eq!(pnhl.stages[3].flow, Flow::On);
    assert_eq!(one_err("BA On AB", "On needs an Xi stage"), "On");
    assert_eq!(
        one_err(
            "B A Xi(1/2) On(1/2) Oa(1/2) Xi(1/2) A B",
            "pairwise thermostat of Oa"
        ),
        "On(1/2)"
    );
    assert_eq!(
        one_err(
            "B A Xi(1/2) Oa(1/2) O(1/2) Xi(1/2) A B",
            "cannot be combined"
        ),
        "Oa(1/2)"
    );
    assert_eq!(one_err("B A Xi(1/2) Oa A B", "Xi coefficients"), "Xi(1/2)");
    let e = compile_with("B A Xi Oa(-1) A B", &options).unwrap_err();
    assert!(e[0].message.contains("Oa is a stochastic sweep"), "{e:?}");
    let e = compile_with("A B(1e400) O", &options).unwrap_err();
    assert!(e[0].message.contains("non-finite"), "{e:?}");
    assert_eq!(one_err("A B(2) O", "B coefficients"), "B(2)");
    assert_eq!(
        one_err(
            "def S(c) = T(c) S(c); A S(1)",
            "recursive sub-scheme: S -> S"
        ),
        "S"
    );
    one_err(
        "def P = Q; def Q = P; A B P O",
        "recursive sub-scheme: P -> Q -> P",
    );
    assert_eq!(one_err("A< B O", "sweep order"), "A<");
    one_err("def A = B; A B O", "sub-flow letter");
    one_err("def H = B; def H = A; H O", "defined twice");
    one_err("let x = 1; let x = 2; A(x) B O", "defined twice");
    one_err("prk(b = [1, 2], bh = [1]) O", "as many b entries");
    one_err("prk(b = [1], bh = [1], kick = O)", "'F' or 'B'");
    one_err("A(foo(2)) B O", "unknown function");
    one_err("A B O é", "unexpected character");
    one_err("let y = 2 A B O", "expected ';'");
    let streams = format!("A B {}", "O(1/256) ".repeat(256));
    assert!(one_err(&streams, "more than 255 random streams").starts_with("O(1/256)"));
    ok(&format!("A B {}", "O(1/255) ".repeat(255)));
    one_err(&format!("A(1{}) B O", "+0".repeat(300)), "nested more than");
    one_err(
        &format!("A({}1{}) B O", "(".repeat(500), ")".repeat(500)),
        "nested more than",
    );
    one_err(
        &format!("A({}1) B O", "-".repeat(100_000)),
        "nested more than",
    );
    let blowup = "def P = A A A A A A A A A A; def Q = P P P P P P P P P P; def R = Q Q Q Q Q Q Q Q Q Q; def U = R R R R R R R R R R; U B O";
    one_err(blowup, "more than 10000");
    let e = err("A B(1/0) O(x) Q");
    assert_eq!(e.len(), 3, "several errors are reported together: {e:?}");
    for d in &e {
        assert!(!d.to_string().is_empty());
    }
}

#[test]
fn prelude_constants_equal_their_written_values() {
    let value = |src: &str| lenient(src).stages[0].coeff.value;
    assert_eq!(value("A(x1) B O"), value("A(1/(2 - 2^(1/3))) B O"));
    assert_eq!(value("A(x0) B O"), value("A(-2^(1/3)/(2 - 2^(1/3))) B O"));
    approx::assert_relative_eq!(value("A(2x1 + x0) B O"), 1.0, max_relative = 1e-15);
}

/// Characters of the language, for random sources.
const ALPHABET: &[char] = &[
    'A', 'B', 'O', 'b', 'T', 'F', 'S', 'Q', 'x', '0', '1', '2', '9', '(', ')', '[', ']', ',', ';',
    '=', '+', '-', '*', '/', '^', '<', '>', '.', 'e', ' ', 's', 'q', 'r', 't',
];

fn from_alphabet() -> impl Strategy<Value = String> {
    prop::collection::vec(prop::sample::select(ALPHABET), 0..80)
        .prop_map(|v| v.into_iter().collect())
}

fn words() -> impl Strategy<Value = String> {
    let word = prop::sample::select(vec![
        "A",
        "B",
        "O",
        "Ob",
        "T",
        "F",
        "S",
        "x1",
        "x0",
        "(",
        ")",
        "1",
        "2",
        "1/2",
        "-",
        "^",
        "/",
        "sqrt(",
        "cbrt(",
        "let ",
        "def ",
        "prk(",
        "b = [",
        "bh = [",
        "]",
        "kick = F",
        ",",
        ";",
        "=",
        "<",
        ">",
        "10^10^10",
        "1/0",
        "0",
        "1e400",
        "H",
        "def H = H;",
        "c",
    ]);
    prop::collection::vec(word, 0..40).prop_map(|v| v.concat())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn never_panics_on_any_string(src in ".*") {
        let _ = compile(&src);
    }

    #[test]
    fn never_panics_on_the_language_alphabet(src in from_alphabet()) {
        check_result(&src);
    }

    #[test]
    fn never_panics_on_language_words(src in words()) {
        check_result(&src);
    }
}

/// Errors have valid spans; programs print to a scheme with the same stage values.
fn check_result(src: &str) {
    for options in [
        Options::default(),
        Options {
            allow_inconsistent: true,
        },
    ] {
        match compile_with(src, &options) {
            Err(errors) => {
                assert!(!errors.is_empty());
                for e in errors {
                    assert!(
                        e.span.start <= e.span.end && e.span.end <= src.len(),
                        "{e:?}"
                    );
                    assert!(src.get(e.span.clone()).is_some(), "{e:?}");
                }
            }
            Ok(p) => {
                assert!(p.stages.iter().all(|s| s.coeff.value.is_finite()));
                let again = compile_with(&p.to_string(), &options).expect("printed form compiles");
                let values = |p: &Program| -> Vec<(Flow, f64, SweepOrder)> {
                    p.stages
                        .iter()
                        .map(|s| (s.flow, s.coeff.value, s.order))
                        .collect()
                };
                assert_eq!(values(&again), values(&p), "{src} -> {p}");
            }
        }
    }
}

mod free_parameters {
    use super::*;
    use dpd_ir::lang::{compile_family, MAX_PARAMETERS};

    const MCLACHLAN: &str = "param l in 0..1/2; B(l) A(1/2) B(1 - 2*l) A(1/2) B(l) O";

    fn family_err(src: &str, needle: &str) -> String {
        let e = compile_family(src).expect_err(src);
        assert_eq!(e.len(), 1, "{src}: {e:?}");
        assert!(e[0].message.contains(needle), "{src}: {}", e[0].message);
        src[e[0].span.clone()].to_string()
    }

    #[test]
    fn a_family_compiles_at_any_point_and_refuses_to_run() {
        let f = compile_family(MCLACHLAN).unwrap();
        assert_eq!(f.names(), ["l"]);
        assert_eq!((f.parameters[0].lo, f.parameters[0].hi), (0.0, 0.5));
        let p = f.at(&[0.25]).unwrap();
        assert_eq!(p.to_string(), "B(0.25000000000000000) A(1/2) B(0.50000000000000000) A(1/2) B(0.25000000000000000) O(1)");
        assert_eq!(p.force_evaluations_per_step(), 2);
        assert_eq!(one_err(MCLACHLAN, "'l' is a free parameter"), "l");
        assert!(f.at(&[]).is_err());
        let yoshida = compile_family("param x in -2..2; S((1 - x)/2) S(x) S((1 - x)/2) O").unwrap();
        let x0 = -(2f64.cbrt()) / (2.0 - 2f64.cbrt());
        assert_eq!(yoshida.at(&[x0]).unwrap().analysis().deterministic_order, 4);
        assert_eq!(
            yoshida.at(&[0.3]).unwrap().analysis().deterministic_order,
            2
        );
    }

    #[test]
    fn bad_declarations_are_errors_on_the_parameter() {
        assert_eq!(
            family_err("param l in 1..1; A(l) B O", "empty range"),
            "param l in 1..1;"
        );
        assert_eq!(
            family_err("param l in 1..0; A(l) B O", "inverted range"),
            "param l in 1..0;"
        );
        assert_eq!(family_err("param l in 0..1; ABO", "not used"), "l");
        assert_eq!(
            family_err(
                "param l in 0..1; let l = 2; A(l) B O",
                "both a free parameter and a constant"
            ),
            "l"
        );
        let four = "param a in 0..1; param b in 0..1; param c in 0..1; param d in 0..1; A(a) B(b) A(c) B(d) O";
        assert_eq!(MAX_PARAMETERS, 3);
        assert_eq!(family_err(four, "at most 3"), "param d in 0..1;");
        assert_eq!(family_err("param l in 0 1; A(l) B O", "'..'"), "1");
    }
}

#[test]
fn cyclic_symmetry() {
    // Symmetric steps, and steps whose repetition is symmetric: OBAB is OBABO with its half
    // sweeps joined, B A B O the same, S(x1)S(x0)S(x1) O has its axis through the sweep.
    for src in [
        "ABOBA",
        "BAOOAB",
        "OBAB",
        "BABO",
        "Ob B A B",
        "S(x1)S(x0)S(x1) O",
        "A(1/3) B O B A(2/3)",
    ] {
        assert!(ok(src).is_cyclically_symmetric(), "{src}");
    }
    // ABO backwards is OBA, which no rotation of ABO is; mirrored sweeps in the same order
    // are not each other's adjoint.
    for src in [
        "ABO",
        "A B(1/3) O B(2/3)",
        "BAO>O>AB",
        "A(1/3) B(1/4) O B(3/4) A(2/3)",
    ] {
        assert!(!ok(src).is_cyclically_symmetric(), "{src}");
    }
}

/// Braces mark a Metropolis-adjusted part: `{` and `}` become stages without a step length,
/// the `}` takes a random stream of its own, nothing merges across them, and the program
/// prints back to a source that compiles to itself.
#[test]
fn metropolis_adjusted_parts() {
    let p = ok("{B(1/2) A B(1/2)} O");
    let flows: Vec<Flow> = p.stages.iter().map(|s| s.flow).collect();
    assert_eq!(
        flows,
        [
            Flow::Propose,
            Flow::B,
            Flow::A,
            Flow::B,
            Flow::Accept,
            Flow::O
        ]
    );
    assert!(p.is_adjusted() && !ok("BAOAB").is_adjusted());
    assert_eq!(p.to_string(), "{ B(1/2) A(1) B(1/2) } O(1)");
    assert_eq!(ok(&p.to_string()).stages, p.stages);
    assert_eq!(format!("{p:#}"), "{ B(1/2) A(1) B(1/2) }@0 O>(1)@0");
    // The same costs as the unadjusted word: one force evaluation, one pair fill.
    let plain = ok("B(1/2) A B(1/2) O");
    assert_eq!(p.evaluations_per_step(), plain.evaluations_per_step());
    // Groups, repetitions and sub-schemes inside; two parts in one step.
    ok("{B[pair](1/2) (B[bond](1/8) A(1/4) B[bond](1/8))^4 B[pair](1/2)} O");
    ok("def H = B(1/4) A(1/2) B(1/4); {H H} Ob");
    let two = ok("{A(1/4) B(1/2) A(1/4)} L {A(1/4) B(1/2) A(1/4)}");
    assert_eq!(
        two.stages.iter().filter(|s| s.flow == Flow::Accept).count(),
        2
    );
    assert!(p.is_symmetric() || !plain.is_symmetric());
}

/// Bad braces are refused at the brace or letter at fault, saying why the Gibbs measure would
/// not be exact.
#[test]
fn metropolis_adjusted_errors() {
    assert_eq!(one_err("{B A B O", "unbalanced"), "{");
    assert_eq!(one_err("B A B} O", "unbalanced"), "}");
    assert_eq!(one_err("{} A B O", "empty braces"), "{}");
    assert_eq!(one_err("{B(1/2) {A} B(1/2)} O", "nested braces"), "{");
    assert_eq!(
        one_err("def H = {B A B}; {H} O", "nested braces"),
        "{B A B}"
    );
    assert_eq!(
        one_err("{B(1/2) A O A B(1/2)}", "O cannot stand inside braces"),
        "O"
    );
    assert_eq!(one_err("B {A} O", "B cannot stand outside the braces"), "B");
    let e = err("{B A B} T");
    assert!(
        e.iter()
            .any(|d| d.message.contains("T cannot stand outside") && d.message.contains("Gibbs")),
        "{e:?}"
    );
    assert_eq!(
        one_err(
            "{B(1/3) A B(2/3)} O",
            "not symmetric: B(1/3) mirrors B(2/3)"
        ),
        "{B(1/3) A B(2/3)}"
    );
    // A zero stage drops out before the test: this one is B(1) between two A(1/2).
    ok("{A(1/2) B A(1/2) B(0)} O");
    one_err("{B A B A} O", "not symmetric");
    // Merged as the program merges: `B(1/4) B(1/4) A B(1/2)` is symmetric.
    ok("{B(1/4) B(1/4) A B(1/2)} O");
}
