//! The tables of sub-flow letters and force groups, shared by the parser, the messages and the
//! docs.

use crate::forces::ForceGroup;
use crate::program::Flow;

/// A letter of the scheme language and the sub-flow it applies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Letter {
    /// How the letter is written in a scheme.
    pub spelling: &'static str,
    pub flow: Flow,
    /// One-line description, as in algorithms.md section 2.
    pub meaning: &'static str,
    /// The force groups the letter may name in brackets (`B[bond]`).
    pub groups: &'static [ForceGroup],
}

/// A force group, as written in brackets after a kick letter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Group {
    pub spelling: &'static str,
    pub group: ForceGroup,
    /// One-line description of the forces it holds.
    pub meaning: &'static str,
}

/// Every force group (module [`crate::forces`]).
pub const GROUPS: [Group; 2] = [
    Group {
        spelling: "pair",
        group: ForceGroup::Pair,
        meaning:
            "the pair forces (in F also their dissipative and random parts) and the body force",
    },
    Group {
        spelling: "bond",
        group: ForceGroup::Bond,
        meaning:
            "the bonded forces: bonds and angles (B only: they have no dissipative or random part)",
    },
];

/// Every sub-flow letter. Spellings start with an uppercase letter followed by lowercase
/// letters only, so that `ObBAB` reads as `Ob B A B`.
pub const LETTERS: [Letter; 10] = [
    Letter {
        spelling: "A",
        flow: Flow::A,
        meaning: "drift q += h p / m",
        groups: &[],
    },
    Letter {
        spelling: "B",
        flow: Flow::B,
        meaning: "conservative kick p += h F^C(q), all forces or one group: B[pair], B[bond]",
        groups: &[ForceGroup::Pair, ForceGroup::Bond],
    },
    Letter {
        spelling: "O",
        flow: Flow::O,
        meaning: "pairwise Ornstein-Uhlenbeck sweep, exact per pair",
        groups: &[],
    },
    Letter {
        spelling: "Ob",
        flow: Flow::Bbk,
        meaning: "pairwise Ornstein-Uhlenbeck sweep with Shardlow's BBK update",
        groups: &[],
    },
    Letter {
        spelling: "T",
        flow: Flow::T,
        meaning: "pairwise conservative + Ornstein-Uhlenbeck sweep, exact per pair",
        groups: &[],
    },
    Letter {
        spelling: "F",
        flow: Flow::F,
        meaning: "explicit full-force kick p += h (F^C + F^D + F^R), all forces or F[pair]",
        groups: &[ForceGroup::Pair],
    },
    Letter {
        spelling: "L",
        flow: Flow::L,
        meaning: "Lowe-Andersen pairwise collisions at rate Gamma, exact in distribution",
        groups: &[],
    },
    Letter {
        spelling: "Oa",
        flow: Flow::Oa,
        meaning: "adaptive pairwise Ornstein-Uhlenbeck sweep (PAdL): friction xi gamma_ij, noise sigma_ij fixed",
        groups: &[],
    },
    Letter {
        spelling: "On",
        flow: Flow::On,
        meaning: "pairwise Nose-Hoover sweep (PNHL): Oa without the pair noise, u *= exp(-xi gamma_ij w_D mu_ij h)",
        groups: &[],
    },
    Letter {
        spelling: "Xi",
        flow: Flow::Xi,
        meaning: "the friction factor xi += h/mu sum gamma_ij w_D (u_ij^2 - kbt (1/m_i + 1/m_j)); OU around 0 with thermostat_friction (PNHL)",
        groups: &[],
    },
];

/// The letter spelled `spelling`, if any.
pub fn letter(spelling: &str) -> Option<&'static Letter> {
    LETTERS.iter().find(|l| l.spelling == spelling)
}

/// The spelling of `flow`: its letter, or the brace `{` or `}` of a Metropolis-adjusted part.
pub fn spelling(flow: Flow) -> &'static str {
    match flow {
        Flow::Propose => "{",
        Flow::Accept => "}",
        _ => LETTERS
            .iter()
            .find(|l| l.flow == flow)
            .map_or("?", |l| l.spelling),
    }
}

/// The force group spelled `spelling`, if any.
pub fn group(spelling: &str) -> Option<&'static Group> {
    GROUPS.iter().find(|g| g.spelling == spelling)
}

/// The spelling of `group`.
pub fn group_spelling(group: ForceGroup) -> &'static str {
    GROUPS
        .iter()
        .find(|g| g.group == group)
        .map_or("?", |g| g.spelling)
}

/// "pair, bond": the force groups, for messages.
pub fn group_spellings() -> String {
    GROUPS
        .iter()
        .map(|g| g.spelling)
        .collect::<Vec<_>>()
        .join(", ")
}

/// "A, B, O, Ob, T, F, L, Oa, Xi": the letters, for messages.
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
    fn module_docs_list_every_letter_and_group() {
        let docs = include_str!("mod.rs");
        for l in LETTERS {
            let row = format!("//! | `{}` | {} |", l.spelling, l.meaning);
            assert!(docs.contains(&row), "missing docs row {row}");
        }
        for g in GROUPS {
            let row = format!("//! | `{}` | {} |", g.spelling, g.meaning);
            assert!(docs.contains(&row), "missing docs row {row}");
        }
    }

    /// README's table of letters has a row for every letter and for every letter with each
    /// group it takes (`B[bond]`), and the macro's documentation names every grouped letter.
    #[test]
    fn user_docs_list_every_letter_and_grouped_letter() {
        let readme = include_str!("../../../README.md");
        let macro_docs = include_str!("../../../src/dpd_scheme.md");
        for l in LETTERS {
            let row = format!("| `{}` |", l.spelling);
            assert!(readme.contains(&row), "README lacks the row {row}");
            for g in l.groups {
                let grouped = format!("`{}[{}]", l.spelling, group_spelling(*g));
                assert!(readme.contains(&grouped), "README lacks {grouped}");
                assert!(
                    macro_docs.contains(&grouped),
                    "dpd_scheme.md lacks {grouped}"
                );
            }
        }
    }

    #[test]
    fn spellings_round_trip() {
        for l in LETTERS {
            assert_eq!(letter(l.spelling), Some(&l));
            assert_eq!(spelling(l.flow), l.spelling);
        }
        assert_eq!(spellings(), "A, B, O, Ob, T, F, L, Oa, On, Xi");
        for g in GROUPS {
            assert_eq!(group(g.spelling), Some(&g));
            assert_eq!(group_spelling(g.group), g.spelling);
        }
        assert_eq!(group_spellings(), "pair, bond");
    }
}
