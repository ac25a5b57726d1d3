//! Force groups: which part of the forces a kick applies, and the kick generators of a step
//! for the consistency check and the order analysis (algorithms.md sections 2 and 4).
//!
//! `B` and `F` apply all forces. `B[pair]` and `F[pair]` apply the pair forces only (with the
//! body force, see [`ForceGroup::Pair`]), `B[bond]` the bonded forces only; `T` applies the
//! pair forces with its Ornstein-Uhlenbeck part. A step that names no group treats all
//! forces as one generator `B`, exactly as before groups existed; a step that names one
//! treats each group it applies as a generator of its own, so multiple time stepping (bonds
//! on an inner step, pairs on the outer one) is checked and analysed like any other splitting.

use crate::program::Flow;
use serde::{Deserialize, Serialize};
use std::fmt;

/// A part of the forces that a kick can apply on its own.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ForceGroup {
    /// The pair forces: the soft repulsion (in `F[pair]` also the pair dissipative and random
    /// forces), and the body force. The body force goes with the pair group because every
    /// scheme applies the pair forces with weights summing to one (the language requires a
    /// pair-force stage), whether or not the system has bonds, and because it is as slow as
    /// they are: in a multiple-time-stepping scheme it belongs on the outer step.
    Pair,
    /// The bonded forces: bonds and angles, evaluated from the bond list, not from the pair
    /// table. They have no dissipative or random part.
    Bond,
}

impl ForceGroup {
    /// Every group, in the order of the enum.
    pub const ALL: [ForceGroup; 2] = [ForceGroup::Pair, ForceGroup::Bond];
}

/// A kick generator: all forces as one (`B`, in a step that names no force group), or one
/// force group.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kick {
    All,
    Group(ForceGroup),
}

impl Kick {
    /// Whether a stage of `flow` restricted to `group` (`None`: the letter's own forces)
    /// advances this generator.
    pub fn advanced_by(self, flow: Flow, group: Option<ForceGroup>) -> bool {
        match self {
            Kick::All => matches!(flow, Flow::B | Flow::T | Flow::F),
            Kick::Group(g) => applies(flow, group, g),
        }
    }

    /// The generator as the language writes it: `B`, `B[pair]`, `B[bond]`.
    pub fn name(self) -> String {
        match self {
            Kick::All => "B".to_string(),
            Kick::Group(g) => format!("B[{}]", crate::lang::letters::group_spelling(g)),
        }
    }

    /// The stages that carry the generator, for messages: `B, T and F`.
    pub fn carriers(self) -> &'static str {
        match self {
            Kick::All => "B, T and F",
            Kick::Group(ForceGroup::Pair) => "B, B[pair], T, F and F[pair]",
            Kick::Group(ForceGroup::Bond) => "B, B[bond] and F",
        }
    }
}

impl fmt::Display for Kick {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name())
    }
}

/// Whether a stage of `flow` restricted to `group` (`None`: the letter's own forces) applies
/// the forces of `g`: B and F apply every group, or the one they name; T applies the pair
/// forces; A, O, Ob, L and the braces apply none.
pub fn applies(flow: Flow, group: Option<ForceGroup>, g: ForceGroup) -> bool {
    match flow {
        Flow::B | Flow::F => group.is_none_or(|named| named == g),
        Flow::T => g == ForceGroup::Pair,
        Flow::A
        | Flow::O
        | Flow::Bbk
        | Flow::L
        | Flow::Oa
        | Flow::On
        | Flow::Xi
        | Flow::Propose
        | Flow::Accept => false,
    }
}

/// The kick generators of a step whose stages are `(flow, group)`: `[All]` when no stage
/// names a group, else the pair forces (which every system has) and each other group some
/// stage applies, in the order of [`ForceGroup::ALL`].
pub fn kicks<I>(stages: I) -> Vec<Kick>
where
    I: IntoIterator<Item = (Flow, Option<ForceGroup>)>,
    I::IntoIter: Clone,
{
    let stages = stages.into_iter();
    if stages.clone().all(|(_, group)| group.is_none()) {
        return vec![Kick::All];
    }
    ForceGroup::ALL
        .into_iter()
        .filter(|&g| {
            g == ForceGroup::Pair || stages.clone().any(|(flow, group)| applies(flow, group, g))
        })
        .map(Kick::Group)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_step_without_groups_has_one_kick() {
        let aboba = [(Flow::A, None), (Flow::B, None), (Flow::O, None)];
        assert_eq!(kicks(aboba), [Kick::All]);
        assert!(Kick::All.advanced_by(Flow::T, None));
        assert!(!Kick::All.advanced_by(Flow::O, None));
    }

    #[test]
    fn a_step_with_groups_has_one_kick_per_group_applied() {
        let pair_only = [(Flow::B, Some(ForceGroup::Pair)), (Flow::T, None)];
        assert_eq!(kicks(pair_only), [Kick::Group(ForceGroup::Pair)]);
        let mts = [(Flow::B, Some(ForceGroup::Bond)), (Flow::T, None)];
        assert_eq!(
            kicks(mts),
            [Kick::Group(ForceGroup::Pair), Kick::Group(ForceGroup::Bond)]
        );
        // An ungrouped B next to a group applies both.
        let mixed = [(Flow::B, Some(ForceGroup::Pair)), (Flow::B, None)];
        assert_eq!(kicks(mixed).len(), 2);
        // The pair forces are a generator even where no stage applies them.
        let bonds_only = [(Flow::B, Some(ForceGroup::Bond))];
        assert_eq!(kicks(bonds_only).len(), 2);
        let bond = Kick::Group(ForceGroup::Bond);
        assert!(bond.advanced_by(Flow::F, None));
        assert!(!bond.advanced_by(Flow::F, Some(ForceGroup::Pair)));
        assert!(!bond.advanced_by(Flow::T, None));
        assert_eq!(bond.name(), "B[bond]");
    }
}
