//! The one table of sub-flow letters, shared by the parser, the messages and the docs.

use crate::program::Flow;

/// A letter of the scheme language and the sub-flow it applies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Letter {
    /// How the letter is written in a scheme.
    pub spelling: &'static str,
    pub flow: Flow,
    /// One-line description, as in algorithms.md section 2.
    pub meaning: &'static str,
}

/// Every sub-flow letter. Spellings start with an uppercase letter followed by lowercase
/// letters only, so that `ObBAB` reads as `Ob B A B`.
pub const LETTERS: [Letter; 6] = [
    Letter {
        spelling: "A",
        flow: Flow::A,
        meaning: "drift q += h p / m",
    },
    Letter {
        spelling: "B",
        flow: Flow::B,
        meaning: "conservative kick p += h F^C(q)",
    },
    Letter {
        spelling: "O",
        flow: Flow::O,
        meaning: "pairwise Ornstein-Uhlenbeck sweep, exact per pair",
    },
    Letter {
        spelling: "Ob",
        flow: Flow::Bbk,
        meaning: "pairwise Ornstein-Uhlenbeck sweep with Shardlow's BBK update",
    },
    Letter {
        spelling: "T",
        flow: Flow::T,
        meaning: "pairwise conservative + Ornstein-Uhlenbeck sweep, exact per pair",
    },
    Letter {
        spelling: "F",
        flow: Flow::F,
        meaning: "explicit full-force kick p += h (F^C + F^D + F^R)",
    },
];

/// The letter spelled `spelling`, if any.
pub fn letter(spelling: &str) -> Option<&'static Letter> {
    LETTERS.iter().find(|l| l.spelling == spelling)
}

/// The spelling of `flow`.
pub fn spelling(flow: Flow) -> &'static str {
    LETTERS
        .iter()
        .find(|l| l.flow == flow)
        .map_or("?", |l| l.spelling)
}

/// "A, B, O, Ob, T, F": the letters, for messages.
pub fn spellings() -> String {
    LETTERS
        .iter()
        .map(|l| l.spelling)
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn module_docs_list_every_letter() {
        let docs = include_str!("mod.rs");
        for l in LETTERS {
            let row = format!("//! | `{}` | {} |", l.spelling, l.meaning);
            assert!(docs.contains(&row), "missing docs row {row}");
        }
    }

    #[test]
    fn spellings_round_trip() {
        for l in LETTERS {
            assert_eq!(letter(l.spelling), Some(&l));
            assert_eq!(spelling(l.flow), l.spelling);
        }
        assert_eq!(spellings(), "A, B, O, Ob, T, F");
    }
}
