//! Coordinates of a Lie element of the free Lie algebra on {A, B} in the Lyndon basis.
//!
//! The Lyndon words over `A < B` of one degree, in lexicographic order, each bracketed by the
//! standard factorisation (`w = u v` with `v` the longest proper Lyndon suffix, `P_w = [P_u,
//! P_v]`), form a basis of the homogeneous part of that degree (the Lyndon basis used by
//! McLachlan and by Blanes, Casas and Murua). Degree 3: `P_AAB = [A,[A,B]]`, `P_ABB = [[A,B],B]
//! = [B,[B,A]]`. The expansion of `P_w` into words is `w` plus words lexicographically greater
//! than `w` (Reutenauer, Free Lie Algebras, thm. 5.1), so the coordinates of a Lie element
//! follow by one pass over the Lyndon words in increasing order.

use std::collections::HashMap;

/// The Lyndon words of length `n` over `letters` (sorted), in lexicographic order (Duval).
pub(crate) fn lyndon_words(letters: &[char], n: usize) -> Vec<String> {
    let k = letters.len();
    let mut out = Vec::new();
    if n == 0 || k == 0 {
        return out;
    }
    let mut w: Vec<usize> = vec![0];
    while !w.is_empty() {
        if w.len() == n {
            out.push(w.iter().map(|&i| letters[i]).collect());
        }
        let m = w.len();
        while w.len() < n {
            let c = w[w.len() - m];
            w.push(c);
        }
        while w.last().is_some_and(|&c| c + 1 == k) {
            w.pop();
        }
        if let Some(last) = w.last_mut() {
            *last += 1;
        }
    }
    out
}

fn is_lyndon(w: &str) -> bool {
    (1..w.len()).all(|i| w < &w[i..])
}

/// The expansion of the standard bracketing of the Lyndon word `w` into words.
pub(crate) fn bracket(w: &str) -> HashMap<String, i64> {
    if w.len() == 1 {
        return HashMap::from([(w.to_string(), 1)]);
    }
    let split = (1..w.len())
        .find(|&i| is_lyndon(&w[i..]))
        .unwrap_or(w.len() - 1);
    let (u, v) = (bracket(&w[..split]), bracket(&w[split..]));
    let mut out: HashMap<String, i64> = HashMap::new();
    for (x, a) in &u {
        for (y, b) in &v {
            *out.entry(format!("{x}{y}")).or_default() += a * b;
            *out.entry(format!("{y}{x}")).or_default() -= a * b;
        }
    }
    out.retain(|_, c| *c != 0);
    out
}

/// The Lyndon coordinates of the homogeneous Lie element of degree `n` whose word
/// coefficients are `coeffs` (words spelled over `letters`; missing words are zero).
pub(crate) fn coordinates(
    letters: &[char],
    n: usize,
    coeffs: &HashMap<String, f64>,
) -> Vec<(String, f64)> {
    let mut rest = coeffs.clone();
    lyndon_words(letters, n)
        .into_iter()
        .map(|w| {
            let c = rest.get(&w).copied().unwrap_or(0.0);
            if c != 0.0 {
                for (word, k) in bracket(&w) {
                    *rest.entry(word).or_default() -= c * k as f64;
                }
            }
            (w, c)
        })
        .collect()
}

/// `AAB` as `[A,[A,B]]`: the standard bracketing written out, the letters `A`, `B`, `C`, ...
/// written as `names` say (`names[0]` for `A`).
pub(crate) fn spell_bracket(w: &str, names: &[String]) -> String {
    if w.len() == 1 {
        let letter = w
            .bytes()
            .next()
            .map_or(0, |c| usize::from(c.wrapping_sub(b'A')));
        return names.get(letter).cloned().unwrap_or_else(|| w.to_string());
    }
    let split = (1..w.len())
        .find(|&i| is_lyndon(&w[i..]))
        .unwrap_or(w.len() - 1);
    format!(
        "[{},{}]",
        spell_bracket(&w[..split], names),
        spell_bracket(&w[split..], names)
    )
}

/// `"-0.0416666667 [A,[A,B]] + 0.0833333333 [[A,B],B]"`, zero coordinates left out, the
/// letters written as `names` say (see [`spell_bracket`]).
pub(crate) fn spell_terms(terms: &[(String, f64)], names: &[String]) -> String {
    let mut s = String::new();
    for (w, c) in terms.iter().filter(|(_, c)| *c != 0.0) {
        let sign = match (s.is_empty(), *c < 0.0) {
            (true, false) => "",
            (true, true) => "-",
            (false, false) => " + ",
            (false, true) => " - ",
        };
        s.push_str(&format!(
            "{sign}{:.10} {}",
            c.abs(),
            spell_bracket(w, names)
        ));
    }
    if s.is_empty() {
        s.push('0');
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lyndon_words_and_dimensions_of_the_free_lie_algebra() {
        assert_eq!(lyndon_words(&['A', 'B'], 3), ["AAB", "ABB"]);
        // Witt's formula on two letters: 2, 1, 2, 3, 6, 9 in degrees 1..=6
        let dims: Vec<usize> = (1..=6)
            .map(|n| lyndon_words(&['A', 'B'], n).len())
            .collect();
        assert_eq!(dims, [2, 1, 2, 3, 6, 9]);
        let names = ["A".to_string(), "B".to_string()];
        assert_eq!(spell_bracket("AAB", &names), "[A,[A,B]]");
        assert_eq!(spell_bracket("ABB", &names), "[[A,B],B]");
        let groups = ["A".to_string(), "B[pair]".into(), "B[bond]".into()];
        assert_eq!(spell_bracket("ABC", &groups), "[A,[B[pair],B[bond]]]");
        assert_eq!(
            bracket("ABB"),
            HashMap::from([("ABB".into(), 1), ("BAB".into(), -2), ("BBA".into(), 1)])
        );
    }

    #[test]
    fn coordinates_recover_a_combination_of_brackets() {
        let mut coeffs: HashMap<String, f64> = HashMap::new();
        for (w, c) in [("AABB", 2.0), ("ABBB", -0.5), ("AAAB", 3.0)] {
            for (word, k) in bracket(w) {
                *coeffs.entry(word).or_default() += c * k as f64;
            }
        }
        let got = coordinates(&['A', 'B'], 4, &coeffs);
        assert_eq!(
            got,
            [
                ("AAAB".to_string(), 3.0),
                ("AABB".to_string(), 2.0),
                ("ABBB".to_string(), -0.5)
            ]
        );
    }
}
