//! The truncated free associative algebra over a generic coefficient field.
//!
//! Hand-written: no crate provides non-commutative truncated power series. Words are finite
//! sequences of letters, each letter carrying a degree (its power of `dt`); a [`Series`]
//! holds the coefficient of every word of degree at most `max_degree` and products drop
//! everything heavier. Products are written as they are multiplied: `x * y` places the words
//! of `x` to the left of the words of `y`. Which side stands for "applied first" is decided by
//! the callers ([`super::hamiltonian`], [`super::invariant`]) and documented there.
//!
//! Storage is dense per word length: the word `l_1 l_2 ... l_n` over `m` letters has index
//! `sum l_i m^(n-i)` (first letter most significant), so concatenation is
//! `index(u v) = index(u) m^|v| + index(v)`.
//!
//! An algebra may also know that some letters commute: each letter may carry a commutation
//! group, and two letters commute when both carry one and the groups differ (the kicks of
//! different force groups, which both move momenta by functions of the positions). Products,
//! exponentials and logarithms are computed in the free algebra; [`Algebra::project`] then
//! maps a series onto the quotient by those relations, whose basis is the canonical words:
//! each maximal run of letters with groups sorted by group, stably (letters of one group keep
//! their order, as they do not commute). The projection is an algebra homomorphism, so
//! projecting a product computed freely gives the product in the quotient.

use std::fmt::Write;

use super::scalar::Scalar;

/// The alphabet, letter degrees and truncation degree of a free algebra.
#[derive(Clone, Debug)]
pub struct Algebra {
    names: Vec<String>,
    weights: Vec<u32>,
    /// The commutation group of each letter (see the module docs); all `None`: no relation.
    groups: Vec<Option<u8>>,
    max_degree: u32,
    /// `word_weights[len][index]`: degree of each word of length `len`.
    word_weights: Vec<Vec<u32>>,
}

/// An element of a truncated free algebra: `terms[len][index]` is the coefficient of a word.
#[derive(Clone, Debug)]
pub struct Series<S> {
    terms: Vec<Vec<S>>,
}

/// A letter of an [`Algebra`], by position in its alphabet.
pub type Letter = usize;

impl Algebra {
    /// An algebra over `letters` (name, degree) whose letters commute as `groups` says (one
    /// entry per letter, see the module docs), truncated above `max_degree`. Degrees below 1
    /// are raised to 1 so that every truncation is finite.
    pub fn commuting(letters: &[(String, u32)], groups: &[Option<u8>], max_degree: u32) -> Algebra {
        let names = letters.iter().map(|(n, _)| n.clone()).collect();
        let weights: Vec<u32> = letters.iter().map(|&(_, w)| w.max(1)).collect();
        let m = weights.len();
        let mut word_weights = vec![vec![0]];
        let max_len = if m == 0 { 0 } else { max_degree as usize };
        for len in 1..=max_len {
            let prev = &word_weights[len - 1];
            let row = (0..prev.len() * m)
                .map(|i| prev[i / m] + weights[i % m])
                .collect();
            word_weights.push(row);
        }
        Algebra {
            names,
            weights,
            groups: groups.to_vec(),
            max_degree,
            word_weights,
        }
    }

    /// Whether some letters commute.
    fn has_relations(&self) -> bool {
        let mut groups = self.groups.iter().flatten();
        groups.next().is_some_and(|g| groups.any(|h| h != g))
    }

    /// The letters of `word`, first letter first.
    fn letters_of(&self, word: Word) -> Vec<Letter> {
        let m = self.letters();
        let mut letters = vec![0; word.len];
        let mut index = word.index;
        for slot in letters.iter_mut().rev() {
            *slot = index % m;
            index /= m;
        }
        letters
    }

    /// The canonical word of `word`'s class: each maximal run of letters with a commutation
    /// group sorted by group, stably.
    pub fn canonical(&self, word: Word) -> Word {
        if !self.has_relations() {
            return word;
        }
        let mut letters = self.letters_of(word);
        let mut start = 0;
        while start < letters.len() {
            let end = (start..letters.len())
                .find(|&i| self.groups[letters[i]].is_none())
                .unwrap_or(letters.len());
            letters[start..end].sort_by_key(|&x| self.groups[x]);
            start = end + 1;
        }
        let m = self.letters();
        Word {
            len: word.len,
            index: letters.iter().fold(0, |i, &x| i * m + x),
        }
    }

    /// How many words the class of `word` holds: for each run of letters with groups, the
    /// number of interleavings of its groups' subsequences (a multinomial coefficient).
    pub fn class_size(&self, word: Word) -> u64 {
        let letters = self.letters_of(word);
        let mut size = 1u64;
        let mut run: Vec<u64> = Vec::new();
        let mut length = 0u64;
        for x in letters.iter().map(Some).chain([None]) {
            match x.and_then(|&x| self.groups[x]) {
                Some(g) => {
                    let g = usize::from(g);
                    if run.len() <= g {
                        run.resize(g + 1, 0);
                    }
                    run[g] += 1;
                    length += 1;
                    // choose which of the run's places this group's letters take
                    size = size * length / run[g];
                }
                None => {
                    run.clear();
                    length = 0;
                }
            }
        }
        size
    }

    /// `x` in the quotient by the commutation relations: every coefficient moved onto the
    /// canonical word of its class.
    pub fn project<S: Scalar>(&self, x: &Series<S>) -> Series<S> {
        if !self.has_relations() {
            return x.clone();
        }
        let mut out: Series<S> = self.zero();
        for (len, row) in x.terms.iter().enumerate() {
            for (index, c) in row.iter().enumerate() {
                if !c.is_zero() {
                    self.add_to(&mut out, self.canonical(Word { len, index }), c);
                }
            }
        }
        out
    }

    fn letters(&self) -> usize {
        self.weights.len()
    }

    fn max_len(&self) -> usize {
        self.word_weights.len() - 1
    }

    pub fn zero<S: Scalar>(&self) -> Series<S> {
        Series {
            terms: self
                .word_weights
                .iter()
                .map(|row| vec![S::zero(); row.len()])
                .collect(),
        }
    }

    pub fn one<S: Scalar>(&self) -> Series<S> {
        let mut s = self.zero();
        s.terms[0][0] = S::ratio(1, 1);
        s
    }

    /// The linear element `sum c_x x` (letters heavier than the truncation are dropped).
    pub fn linear<S: Scalar>(&self, terms: &[(Letter, S)]) -> Series<S> {
        let mut s: Series<S> = self.zero();
        for (x, c) in terms {
            if s.terms.len() > 1 && *x < self.letters() && self.weights[*x] <= self.max_degree {
                s.terms[1][*x] = s.terms[1][*x].plus(c);
            }
        }
        s
    }

    /// The truncated product `x y` (words of `x` on the left).
    pub fn mul<S: Scalar>(&self, x: &Series<S>, y: &Series<S>) -> Series<S> {
        let m = self.letters();
        let y_nonzero: Vec<Vec<(usize, u32, &S)>> = y
            .terms
            .iter()
            .zip(&self.word_weights)
            .map(|(row, weights)| {
                row.iter()
                    .enumerate()
                    .filter(|(_, c)| !c.is_zero())
                    .map(|(i, c)| (i, weights[i], c))
                    .collect()
            })
            .collect();
        let mut out: Series<S> = self.zero();
        for (lx, row) in x.terms.iter().enumerate() {
            for (ix, a) in row.iter().enumerate() {
                if a.is_zero() {
                    continue;
                }
                let wx = self.word_weights[lx][ix];
                let mut shift = 1;
                for (ly, ys) in y_nonzero.iter().enumerate() {
                    if lx + ly > self.max_len() {
                        break;
                    }
                    let target = &mut out.terms[lx + ly];
                    for &(iy, wy, b) in ys {
                        if wx + wy <= self.max_degree {
                            let slot = &mut target[ix * shift + iy];
                            *slot = slot.plus(&a.times(b));
                        }
                    }
                    shift *= m;
                }
            }
        }
        out
    }

    /// `exp(x)` for an element without constant term.
    pub fn exp<S: Scalar>(&self, x: &Series<S>) -> Series<S> {
        let mut x = x.clone();
        x.terms[0][0] = S::zero();
        let mut sum = self.one();
        let mut power = self.one();
        let mut factorial: i64 = 1;
        for k in 1..=i64::from(self.max_degree) {
            power = self.mul(&power, &x);
            factorial = factorial.saturating_mul(k);
            sum.add_scaled(&power, &S::ratio(1, factorial));
        }
        sum
    }

    /// `log(x)` for an element with constant term 1 (the constant term is ignored).
    pub fn log<S: Scalar>(&self, x: &Series<S>) -> Series<S> {
        let mut x = x.clone();
        x.terms[0][0] = S::zero();
        let mut sum = self.zero();
        let mut power = self.one();
        for n in 1..=i64::from(self.max_degree) {
            power = self.mul(&power, &x);
            let sign = if n % 2 == 1 { 1 } else { -1 };
            sum.add_scaled(&power, &S::ratio(sign, n));
        }
        sum
    }

    /// Every word of degree `degree` with its coefficient, shortest words first.
    pub fn terms_of_degree<'a, S>(
        &'a self,
        x: &'a Series<S>,
        degree: u32,
    ) -> impl Iterator<Item = (Word, &'a S)> + 'a {
        x.terms
            .iter()
            .zip(&self.word_weights)
            .enumerate()
            .flat_map(move |(len, (row, weights))| {
                row.iter()
                    .zip(weights)
                    .enumerate()
                    .filter(move |(_, (_, &w))| w == degree)
                    .map(move |(index, (c, _))| (Word { len, index }, c))
            })
    }

    /// The last letter of a non-empty word and the word without it.
    pub fn split_last(&self, word: Word) -> Option<(Word, Letter)> {
        let m = self.letters();
        (word.len > 0).then(|| {
            let prefix = Word {
                len: word.len - 1,
                index: word.index / m,
            };
            (prefix, word.index % m)
        })
    }

    /// `word` followed by `letter`.
    pub fn append(&self, word: Word, letter: Letter) -> Word {
        Word {
            len: word.len + 1,
            index: word.index * self.letters() + letter,
        }
    }

    /// Adds `c` to the coefficient of `word` (ignored if the word is heavier than the
    /// truncation).
    pub fn add_to<S: Scalar>(&self, x: &mut Series<S>, word: Word, c: &S) {
        if let Some(slot) = x
            .terms
            .get_mut(word.len)
            .and_then(|r| r.get_mut(word.index))
        {
            *slot = slot.plus(c);
        }
    }

    /// The word spelled with letter names (`"O1AB"`; the empty word is `"1"`).
    pub fn spell(&self, word: Word) -> String {
        let m = self.letters();
        let mut letters = Vec::with_capacity(word.len);
        let mut index = word.index;
        for _ in 0..word.len {
            letters.push(index % m);
            index /= m;
        }
        if letters.is_empty() {
            return "1".to_string();
        }
        letters.iter().rev().fold(String::new(), |mut s, &l| {
            let _ = write!(s, "{}", self.names[l]);
            s
        })
    }
}

/// A word of an [`Algebra`]: its length and dense index.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Word {
    len: usize,
    index: usize,
}

impl<S: Scalar> Series<S> {
    /// `self += c * x`.
    fn add_scaled(&mut self, x: &Series<S>, c: &S) {
        for (mine, theirs) in self.terms.iter_mut().zip(&x.terms) {
            for (a, b) in mine.iter_mut().zip(theirs) {
                if !b.is_zero() {
                    *a = a.plus(&b.times(c));
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::scalar::Rational;
    use super::*;

    fn ab(max_degree: u32) -> Algebra {
        Algebra::commuting(
            &[("A".into(), 1), ("B".into(), 1)],
            &[None, None],
            max_degree,
        )
    }

    fn coeff(alg: &Algebra, x: &Series<Rational>, word: &str) -> String {
        let degree = word.len() as u32;
        alg.terms_of_degree(x, degree)
            .find(|(w, _)| alg.spell(*w) == word)
            .map(|(_, c)| c.to_string())
            .unwrap_or_default()
    }

    #[test]
    fn log_of_exp_is_identity_and_bch_commutator_appears() {
        let alg = ab(3);
        let a = alg.linear(&[(0, Rational::ratio(1, 1))]);
        let b = alg.linear(&[(1, Rational::ratio(1, 1))]);
        let l = alg.log(&alg.mul(&alg.exp(&a), &alg.exp(&b)));
        // log(e^A e^B) = A + B + [A,B]/2 + ([A,[A,B]] + [B,[B,A]])/12 + ...
        assert_eq!(coeff(&alg, &l, "A"), "1");
        assert_eq!(coeff(&alg, &l, "AB"), "1/2");
        assert_eq!(coeff(&alg, &l, "BA"), "-1/2");
        assert_eq!(coeff(&alg, &l, "AA"), "0");
        assert_eq!(coeff(&alg, &l, "AAB"), "1/12");
        assert_eq!(coeff(&alg, &l, "ABA"), "-1/6");
        assert_eq!(coeff(&alg, &l, "BBA"), "1/12");
    }

    #[test]
    fn heavy_letters_are_truncated() {
        let alg = Algebra::commuting(&[("A".into(), 1), ("E".into(), 3)], &[None, None], 3);
        let x = alg.linear(&[(0, 1.0), (1, 1.0)]);
        let e = alg.exp(&x);
        let nonzero: Vec<usize> = (0..=4)
            .map(|d| {
                alg.terms_of_degree(&e, d)
                    .filter(|(_, c)| **c != 0.0)
                    .count()
            })
            .collect();
        // nonzero words of degree 0..3: 1; A; AA; AAA and E; nothing of degree 4 is kept
        assert_eq!(nonzero, [1, 1, 1, 2, 0]);
        let (e_word, _) = alg.terms_of_degree(&e, 3).next().unwrap();
        assert_eq!(alg.spell(e_word), "E");
        assert_eq!(
            alg.split_last(e_word).map(|(p, l)| (alg.spell(p), l)),
            Some(("1".into(), 1))
        );
    }

    /// With P and Q commuting, `exp(P) exp(Q) = exp(P + Q)` in the quotient, though not in
    /// the free algebra; `A` commutes with neither, so `APQ` and `PAQ` stay apart.
    #[test]
    fn commuting_letters_are_projected_onto_canonical_words() {
        let letters = [("A".into(), 1), ("P".into(), 1), ("Q".into(), 1)];
        let alg = Algebra::commuting(&letters, &[None, Some(0), Some(1)], 4);
        let (p, q) = (
            alg.linear(&[(1, Rational::ratio(1, 1))]),
            alg.linear(&[(2, Rational::ratio(1, 1))]),
        );
        let product = alg.mul(&alg.exp(&p), &alg.exp(&q));
        let sum = alg.exp(&alg.linear(&[(1, Rational::ratio(1, 1)), (2, Rational::ratio(1, 1))]));
        assert_eq!(coeff(&alg, &product, "QP"), "0");
        let (product, sum) = (alg.project(&product), alg.project(&sum));
        for degree in 0..=4 {
            let a: Vec<String> = alg
                .terms_of_degree(&product, degree)
                .map(|(_, c)| c.to_string())
                .collect();
            let b: Vec<String> = alg
                .terms_of_degree(&sum, degree)
                .map(|(_, c)| c.to_string())
                .collect();
            assert_eq!(a, b, "degree {degree}");
        }
        // PQ and QP are one class of two words, PQP Q of 4!/(2!2!) = 6 when run together
        assert_eq!(coeff(&alg, &sum, "PQ"), "1");
        let word = |w: &str| {
            alg.terms_of_degree(&sum, w.len() as u32)
                .find(|(x, _)| alg.spell(*x) == w)
                .unwrap()
                .0
        };
        assert_eq!(alg.spell(alg.canonical(word("QP"))), "PQ");
        assert_eq!(alg.spell(alg.canonical(word("QAQP"))), "QAPQ");
        assert_eq!(alg.class_size(word("PQPQ")), 6);
        assert_eq!(alg.class_size(word("PAQP")), 2);
        assert_eq!(alg.class_size(word("AAAA")), 1);
    }
}
