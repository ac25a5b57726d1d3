//! Deterministic order of the Hamiltonian part (algorithms.md section 4.2).
//!
//! O and Bbk stages are dropped; T and F act as B with their coefficient. The step is the
//! product `exp(c_1 X_1) exp(c_2 X_2) ...` over the stages in application order (first applied
//! leftmost: the Lie-derivative convention, `f -> f o phi_n o ... o phi_1`), with `dt` scaled
//! out so that a word of length `n` carries `dt^n`. It is compared with `exp(A + B)`, where
//! every word of length `n` has coefficient `1/n!`. That target is invariant under reversing
//! words, so the order does not depend on which end is written first.

use super::algebra::{Algebra, Letter, Series};
use super::lyndon;
use super::scalar::Scalar;
use crate::program::{Flow, Stage};

pub(crate) const A: Letter = 0;
pub(crate) const B: Letter = 1;

/// An order found by comparing word coefficients up to a maximal degree.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Order {
    pub order: u32,
    /// All degrees checked matched: the true order is at least `order`.
    pub capped: bool,
}

/// The Hamiltonian factors `(letter, coefficient)` in application order, adjacent equal letters
/// merged (they commute).
pub(crate) fn hamiltonian_factors<S: Scalar>(stages: &[Stage], coeffs: &[S]) -> Vec<(Letter, S)> {
    let mut factors: Vec<(Letter, S)> = Vec::new();
    for (stage, c) in stages.iter().zip(coeffs) {
        let letter = match stage.flow {
            Flow::A => A,
            Flow::B | Flow::T | Flow::F => B,
            Flow::O | Flow::Bbk => continue,
        };
        match factors.last_mut() {
            Some((last, sum)) if *last == letter => *sum = sum.plus(c),
            _ => factors.push((letter, c.clone())),
        }
    }
    factors
}

/// The algebra over A, B truncated above `max_degree`.
pub(crate) fn hamiltonian_algebra(max_degree: u32) -> Algebra {
    Algebra::new(&[("A".into(), 1), ("B".into(), 1)], max_degree)
}

/// The product of `exp(c X)` over `factors`, left to right.
pub(crate) fn product<S: Scalar>(alg: &Algebra, factors: &[(Letter, S)]) -> Series<S> {
    factors.iter().fold(alg.one(), |acc, (x, c)| {
        let e = alg.exp(&alg.linear(&[(*x, c.clone())]));
        alg.mul(&acc, &e)
    })
}

/// The largest `p <= max_degree` such that every word of length `<= p` has the coefficient of
/// `exp(A + B)`. In `f64` a word of length `n` matches when it is within
/// `FLOAT_TOLERANCE * max(1, C)^n / n!` of `1/n!`, `C` the sum of absolute coefficients: that
/// bounds the magnitude of every term summed into the coefficient.
pub(crate) fn deterministic_order<S: Scalar>(factors: &[(Letter, S)], max_degree: u32) -> Order {
    let alg = hamiltonian_algebra(max_degree);
    let p = product(&alg, factors);
    let c: f64 = factors.iter().map(|(_, c)| c.to_f64().abs()).sum();
    let mut factorial: i64 = 1;
    for n in 1..=max_degree {
        factorial = factorial.saturating_mul(i64::from(n));
        let target = S::ratio(1, factorial);
        let scale = c.max(1.0).powi(n as i32) / factorial as f64;
        if !alg
            .terms_of_degree(&p, n)
            .all(|(_, w)| w.minus(&target).negligible(scale))
        {
            return Order {
                order: n - 1,
                capped: false,
            };
        }
    }
    Order {
        order: max_degree,
        capped: true,
    }
}

/// The word coefficients of the step minus those of `exp(A + B)`, degrees 2 to `order`: all
/// zero iff the deterministic order is at least `order` (given consistency).
pub(crate) fn deterministic_residuals(factors: &[(Letter, f64)], order: u32) -> Vec<f64> {
    let alg = hamiltonian_algebra(order);
    let p = product(&alg, factors);
    let mut factorial = 1.0;
    let mut out = Vec::new();
    for n in 1..=order {
        factorial *= f64::from(n);
        if n >= 2 {
            out.extend(alg.terms_of_degree(&p, n).map(|(_, c)| c - 1.0 / factorial));
        }
    }
    out
}

/// The leading error term of the Hamiltonian part: `log(step) - (A + B)` at degree
/// `order + 1`, as coordinates in the Lyndon basis (module `lyndon`), with its Euclidean norm.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct LeadingError {
    /// `(Lyndon word, coefficient)`, every Lyndon word of the degree in lexicographic order.
    pub terms: Vec<(String, f64)>,
    /// `sqrt(sum of squared coefficients)`.
    pub norm: f64,
}

/// The leading error of a step of deterministic order `order`. Below degree `order + 1` the
/// step agrees with `exp(A + B)`, so at that degree `step - exp(A + B)` equals
/// `log(step) - (A + B)`, a Lie element.
pub(crate) fn leading_error<S: Scalar>(factors: &[(Letter, S)], order: u32) -> LeadingError {
    let degree = order + 1;
    let alg = hamiltonian_algebra(degree);
    let p = product(&alg, factors);
    let factorial: i64 = (1..=i64::from(degree)).product();
    let target = S::ratio(1, factorial);
    let words = alg
        .terms_of_degree(&p, degree)
        .map(|(w, c)| (alg.spell(w), c.minus(&target).to_f64()))
        .collect();
    let terms = lyndon::coordinates(&['A', 'B'], degree as usize, &words);
    let norm = terms.iter().map(|(_, c)| c * c).sum::<f64>().sqrt();
    LeadingError { terms, norm }
}

#[cfg(test)]
mod tests {
    use super::super::scalar::Rational;
    use super::*;
    use proptest::prelude::*;

    fn palindrome(
        half: &[(bool, i64, i64)],
        middle: Option<(bool, i64, i64)>,
    ) -> Vec<(Letter, Rational)> {
        let letter = |is_a: bool| if is_a { A } else { B };
        let mut seq: Vec<(Letter, Rational)> = half
            .iter()
            .map(|&(a, n, d)| (letter(a), Rational::ratio(n, d)))
            .collect();
        let back: Vec<_> = seq.iter().rev().cloned().collect();
        if let Some((a, n, d)) = middle {
            seq.push((letter(a), Rational::ratio(n, d)));
        }
        seq.extend(back);
        seq
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        /// A palindromic product `P` satisfies `P(-dt) P(dt) = 1`, so its logarithm has only odd
        /// powers of dt: in particular no first-order term (`dt^2` words).
        #[test]
        fn palindromes_have_no_even_log_terms(
            half in prop::collection::vec((any::<bool>(), -6i64..7, 1i64..7), 0..4),
            middle in prop::option::of((any::<bool>(), -6i64..7, 1i64..7)),
        ) {
            let seq = palindrome(&half, middle);
            let alg = hamiltonian_algebra(6);
            let log = alg.log(&product(&alg, &seq));
            for degree in [2, 4, 6] {
                for (w, c) in alg.terms_of_degree(&log, degree) {
                    prop_assert!(c.is_zero(), "{} has coefficient {}", alg.spell(w), c);
                }
            }
        }

        /// Consistent palindromes (A and B sums one) are at least second order.
        #[test]
        fn consistent_palindromes_are_second_order(
            half in prop::collection::vec((any::<bool>(), -6i64..7, 1i64..7), 0..4),
        ) {
            let mut seq = palindrome(&half, None);
            let (mut a, mut b) = (Rational::ratio(1, 1), Rational::ratio(1, 1));
            for (x, c) in &seq {
                let s = if *x == A { &mut a } else { &mut b };
                *s = s.minus(c);
            }
            // make the sums one with a symmetric B(b/2) A(a) B(b/2) core
            let half_b = b.times(&Rational::ratio(1, 2));
            let mid = seq.len() / 2;
            seq.splice(mid..mid, [(B, half_b.clone()), (A, a), (B, half_b)]);
            prop_assert!(deterministic_order(&seq, 4).order >= 2);
        }
    }

    #[test]
    fn velocity_verlet_is_second_order_exactly() {
        let vv = [
            (B, Rational::ratio(1, 2)),
            (A, Rational::ratio(1, 1)),
            (B, Rational::ratio(1, 2)),
        ];
        assert_eq!(
            deterministic_order(&vv, 8),
            Order {
                order: 2,
                capped: false
            }
        );
        let lie = [(A, 1.0), (B, 1.0)];
        assert_eq!(
            deterministic_order(&lie, 8),
            Order {
                order: 1,
                capped: false
            }
        );
        let exact_flow: [(Letter, f64); 0] = [];
        assert_eq!(deterministic_order(&exact_flow, 8).order, 0);
    }

    #[test]
    fn strang_leading_coefficients_in_the_lyndon_basis() {
        let half = Rational::ratio(1, 2);
        let one = Rational::ratio(1, 1);
        // A(1/2) B A(1/2): log = A + B - 1/24 [A,[A,B]] + 1/12 [B,[B,A]] + O(dt^5)
        let aba = [(A, half.clone()), (B, one.clone()), (A, half.clone())];
        let e = leading_error(&aba, 2);
        assert_eq!(
            e.terms,
            [
                ("AAB".to_string(), -1.0 / 24.0),
                ("ABB".to_string(), 1.0 / 12.0)
            ]
        );
        assert!((e.norm - 5f64.sqrt() / 24.0).abs() < 1e-15);
        // B(1/2) A B(1/2): the roles swap
        let bab = [(B, half.clone()), (A, one), (B, half)];
        let e = leading_error(&bab, 2);
        assert_eq!(
            e.terms,
            [
                ("AAB".to_string(), 1.0 / 12.0),
                ("ABB".to_string(), -1.0 / 24.0)
            ]
        );
        // Lie-Trotter A B: log = A + B + 1/2 [A,B]
        let lie = [(A, 1.0), (B, 1.0)];
        assert_eq!(leading_error(&lie, 1).terms, [("AB".to_string(), 0.5)]);
    }
}
