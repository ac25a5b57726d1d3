//! Deterministic order of the Hamiltonian part (algorithms.md section 4.2).
//!
//! O and Bbk stages are dropped; T and F act as kicks with their coefficient. The alphabet is
//! A and the kick generators of the step (module [`crate::forces`]): `B` alone in a step that
//! names no force group, else one letter per force group. The step is the product
//! `exp(c_1 X_1) exp(c_2 X_2) ...` over the stages in application order (first applied
//! leftmost: the Lie-derivative convention, `f -> f o phi_n o ... o phi_1`), a kick of several
//! groups contributing `exp(c (X + Y))`, with `dt` scaled out so that a word of length `n`
//! carries `dt^n`. It is compared with `exp(A + B_1 + ...)`, where every word of length `n`
//! has coefficient `1/n!`. That target is invariant under reversing words, so the order does
//! not depend on which end is written first. Kicks of different force groups commute (both
//! move momenta by functions of the positions): with groups the comparison is made in the
//! quotient by that relation (module `algebra`), where a class of `k` words has the target
//! coefficient `k/n!`. So a scheme whose groups always appear together, `B[pair](c) B[bond](c)`
//! for every `B(c)`, has the orders of the scheme without groups.

use super::algebra::{Algebra, Letter, Series, Word};
use super::lyndon;
use super::scalar::Scalar;
use crate::forces::kicks;
use crate::program::{Flow, Stage};

pub(crate) const A: Letter = 0;

/// An order found by comparing word coefficients up to a maximal degree.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Order {
    pub order: u32,
    /// All degrees checked matched: the true order is at least `order`.
    pub capped: bool,
}

/// The Hamiltonian part of a step: its alphabet and its factors.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Hamiltonian<S> {
    /// The letters as reports write them: `A`, then `B`, or `B[pair]` and `B[bond]`.
    pub names: Vec<String>,
    /// `(letters, c)` for each factor `exp(c (X_1 + X_2 + ...))`, in application order,
    /// adjacent factors of the same letters merged (they commute).
    pub factors: Vec<(Vec<Letter>, S)>,
}

/// The Hamiltonian part of `stages` with coefficients `coeffs`.
pub(crate) fn hamiltonian_factors<S: Scalar>(stages: &[Stage], coeffs: &[S]) -> Hamiltonian<S> {
    let kicks = kicks(stages.iter().map(|s| (s.flow, s.group)));
    let names = std::iter::once("A".to_string())
        .chain(kicks.iter().map(|k| k.name()))
        .collect();
    let mut factors: Vec<(Vec<Letter>, S)> = Vec::new();
    for (stage, c) in stages.iter().zip(coeffs) {
        let letters: Vec<Letter> = match stage.flow {
            Flow::A => vec![A],
            Flow::B | Flow::T | Flow::F => (1..)
                .zip(&kicks)
                .filter(|(_, k)| k.advanced_by(stage.flow, stage.group))
                .map(|(x, _)| x)
                .collect(),
            // The thermostats are not part of the Hamiltonian splitting.
            Flow::O | Flow::Bbk | Flow::L | Flow::Oa | Flow::On | Flow::Xi => continue,
            // The braces of a Metropolis-adjusted part: the word they hold is analysed
            // unadjusted.
            Flow::Propose | Flow::Accept => continue,
        };
        match factors.last_mut() {
            Some((last, sum)) if *last == letters => *sum = sum.plus(c),
            _ => factors.push((letters, c.clone())),
        }
    }
    Hamiltonian { names, factors }
}

impl<S: Scalar> Hamiltonian<S> {
    /// The algebra over the letters, the kicks commuting with each other, truncated above
    /// `max_degree`; its letters are named `A`, `B`, `C`, ... (one character each, for the
    /// Lyndon basis).
    fn algebra(&self, max_degree: u32) -> Algebra {
        let letters: Vec<(String, u32)> = (b'A'..)
            .take(self.names.len())
            .map(|c| (char::from(c).to_string(), 1))
            .collect();
        let groups: Vec<Option<u8>> = (0..self.names.len())
            .map(|x| (x != A).then(|| u8::try_from(x).unwrap_or(u8::MAX)))
            .collect();
        Algebra::commuting(&letters, &groups, max_degree)
    }

    /// Whether the step has several kick letters, which commute: the Lyndon basis of the
    /// free Lie algebra then does not describe its errors.
    fn grouped(&self) -> bool {
        self.names.len() > 2
    }

    /// The product of the factors' exponentials, left to right, in the quotient where
    /// kicks commute.
    fn product(&self, alg: &Algebra) -> Series<S> {
        let free = self.factors.iter().fold(alg.one(), |acc, (letters, c)| {
            let terms: Vec<(Letter, S)> = letters.iter().map(|&x| (x, c.clone())).collect();
            alg.mul(&acc, &alg.exp(&alg.linear(&terms)))
        });
        alg.project(&free)
    }

    /// The sum of the absolute coefficients: a bound on the size of the terms summed into a
    /// word coefficient.
    fn size(&self) -> f64 {
        self.factors.iter().map(|(_, c)| c.to_f64().abs()).sum()
    }
}

/// The canonical words of degree `n` of `p` with their coefficients minus those of
/// `exp(A + B + ...)` (`k/n!` for a class of `k` words), and each class's size.
fn defects<'a, S: Scalar>(
    alg: &'a Algebra,
    p: &'a Series<S>,
    n: u32,
) -> impl Iterator<Item = (Word, S, u64)> + 'a {
    let factorial: i64 = (1..=i64::from(n)).product();
    alg.terms_of_degree(p, n)
        .filter(move |(w, _)| alg.canonical(*w) == *w)
        .map(move |(w, c)| {
            let size = alg.class_size(w);
            let target = S::ratio(i64::try_from(size).unwrap_or(i64::MAX), factorial);
            (w, c.minus(&target), size)
        })
}

/// The largest `p <= max_degree` such that every word (class) of length `<= p` has the
/// coefficient of `exp(A + B + ...)`. In `f64` a class of `k` words of length `n` matches when
/// it is within `FLOAT_TOLERANCE * k max(1, C)^n / n!` of `k/n!`, `C` the sum of absolute
/// coefficients: that bounds the magnitude of every term summed into the coefficient.
pub(crate) fn deterministic_order<S: Scalar>(h: &Hamiltonian<S>, max_degree: u32) -> Order {
    let alg = h.algebra(max_degree);
    let p = h.product(&alg);
    let c = h.size();
    let mut factorial: i64 = 1;
    for n in 1..=max_degree {
        factorial = factorial.saturating_mul(i64::from(n));
        let scale = c.max(1.0).powi(n as i32) / factorial as f64;
        if !defects(&alg, &p, n).all(|(_, d, k)| d.negligible(scale * k as f64)) {
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

/// The word coefficients of the step minus those of `exp(A + B + ...)`, degrees 2 to `order`:
/// all zero iff the deterministic order is at least `order` (given consistency).
pub(crate) fn deterministic_residuals(h: &Hamiltonian<f64>, order: u32) -> Vec<f64> {
    let alg = h.algebra(order);
    let p = h.product(&alg);
    (2..=order)
        .flat_map(|n| defects(&alg, &p, n).map(|(_, d, _)| d).collect::<Vec<_>>())
        .collect()
}

/// The leading error term of the Hamiltonian part: `log(step) - (A + B + ...)` at degree
/// `order + 1`, as coordinates in the Lyndon basis (module `lyndon`), with its Euclidean norm.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct LeadingError {
    /// `(Lyndon word, coefficient)`, every Lyndon word of the degree in lexicographic order,
    /// spelled with the one-character letters `A`, `B`, `C`, ... of the algebra.
    pub terms: Vec<(String, f64)>,
    /// `sqrt(sum of squared coefficients)`.
    pub norm: f64,
}

/// The leading error of a step of deterministic order `order`. Below degree `order + 1` the
/// step agrees with `exp(A + B + ...)`, so at that degree the difference equals
/// `log(step) - (A + B + ...)`, a Lie element. `None` for a step with several kick letters,
/// whose commutation the Lyndon basis of the free Lie algebra does not express.
pub(crate) fn leading_error<S: Scalar>(h: &Hamiltonian<S>, order: u32) -> Option<LeadingError> {
    if h.grouped() {
        return None;
    }
    let degree = order + 1;
    let alg = h.algebra(degree);
    let p = h.product(&alg);
    let factorial: i64 = (1..=i64::from(degree)).product();
    let target = S::ratio(1, factorial);
    let words = alg
        .terms_of_degree(&p, degree)
        .map(|(w, c)| (alg.spell(w), c.minus(&target).to_f64()))
        .collect();
    let letters: Vec<char> = (b'A'..).take(h.names.len()).map(char::from).collect();
    let terms = lyndon::coordinates(&letters, degree as usize, &words);
    let norm = terms.iter().map(|(_, c)| c * c).sum::<f64>().sqrt();
    Some(LeadingError { terms, norm })
}

#[cfg(test)]
mod tests {
    use super::super::scalar::Rational;
    use super::*;
    use proptest::prelude::*;

    const B: Letter = 1;

    /// The Hamiltonian part over A and B with factors `seq`.
    fn ab<S: Scalar>(seq: &[(Letter, S)]) -> Hamiltonian<S> {
        Hamiltonian {
            names: vec!["A".into(), "B".into()],
            factors: seq.iter().map(|(x, c)| (vec![*x], c.clone())).collect(),
        }
    }

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
            let h = ab(&palindrome(&half, middle));
            let alg = h.algebra(6);
            let log = alg.log(&h.product(&alg));
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
            prop_assert!(deterministic_order(&ab(&seq), 4).order >= 2);
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
            deterministic_order(&ab(&vv), 8),
            Order {
                order: 2,
                capped: false
            }
        );
        let lie = [(A, 1.0), (B, 1.0)];
        assert_eq!(
            deterministic_order(&ab(&lie), 8),
            Order {
                order: 1,
                capped: false
            }
        );
        let exact_flow: [(Letter, f64); 0] = [];
        assert_eq!(deterministic_order(&ab(&exact_flow), 8).order, 0);
    }

    #[test]
    fn strang_leading_coefficients_in_the_lyndon_basis() {
        let half = Rational::ratio(1, 2);
        let one = Rational::ratio(1, 1);
        // A(1/2) B A(1/2): log = A + B - 1/24 [A,[A,B]] + 1/12 [B,[B,A]] + O(dt^5)
        let aba = [(A, half.clone()), (B, one.clone()), (A, half.clone())];
        let e = leading_error(&ab(&aba), 2).unwrap();
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
        let e = leading_error(&ab(&bab), 2).unwrap();
        assert_eq!(
            e.terms,
            [
                ("AAB".to_string(), 1.0 / 12.0),
                ("ABB".to_string(), -1.0 / 24.0)
            ]
        );
        // Lie-Trotter A B: log = A + B + 1/2 [A,B]
        let lie = [(A, 1.0), (B, 1.0)];
        assert_eq!(
            leading_error(&ab(&lie), 1).unwrap().terms,
            [("AB".to_string(), 0.5)]
        );
    }
}
