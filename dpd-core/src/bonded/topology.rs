//! [`Topology`]: the bonds and angles of a system by particle id, validated at construction.

use super::{AngleStyle, BondStyle};
use crate::error::ParamError;
use serde::{Deserialize, Serialize};

/// A bond between the particles with ids `i` and `j`, of bond type `kind` (an index into
/// [`Topology::bond_types`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Bond {
    pub i: u32,
    pub j: u32,
    pub kind: u16,
}

/// An angle `i - j - k` with its vertex at the particle with id `j`, of angle type `kind` (an
/// index into [`Topology::angle_types`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Angle {
    pub i: u32,
    pub j: u32,
    pub k: u32,
    pub kind: u16,
}

/// The bonded interactions of a system: bond and angle types with their coefficients, and the
/// bonds and angles between particles named by id ([`crate::System::ids`]: the index a particle
/// had when the system was built, whatever its storage order now).
///
/// Bonded beads keep their soft pair repulsion (the DPD convention): a bond adds to the pair
/// forces, it does not exclude the pair, unless the system is built with
/// [`crate::SystemBuilder::exclude_bonded`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "TopologyBuilder", into = "TopologyBuilder")]
pub struct Topology {
    particles: usize,
    bond_types: Vec<BondStyle>,
    bonds: Vec<Bond>,
    angle_types: Vec<AngleStyle>,
    angles: Vec<Angle>,
}

/// Unvalidated topology; [`TopologyBuilder::build`] checks it. Default: no types, no bonds.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TopologyBuilder {
    /// The number of particles of the system the ids refer to (ids are `0..particles`).
    pub particles: usize,
    pub bond_types: Vec<BondStyle>,
    pub bonds: Vec<Bond>,
    pub angle_types: Vec<AngleStyle>,
    pub angles: Vec<Angle>,
}

impl TopologyBuilder {
    /// Check every coefficient, id and type: coefficients finite and positive (see
    /// [`BondStyle`], [`AngleStyle`]), ids `< particles`, the particles of a bond or an angle
    /// distinct, types in range. An error names the bond or angle by index and its ids.
    pub fn build(self) -> Result<Topology, ParamError> {
        for (t, style) in self.bond_types.iter().enumerate() {
            style.check(&format!("bond_types[{t}]"))?;
        }
        for (t, style) in self.angle_types.iter().enumerate() {
            style.check(&format!("angle_types[{t}]"))?;
        }
        for (b, bond) in self.bonds.iter().enumerate() {
            // Messages are formatted only on failure: set-up of a large melt checks every bond.
            let what = || format!("bond {b} (ids {}, {})", bond.i, bond.j);
            let field = |name: &str| format!("bonds[{b}].{name}");
            self.check_ids(what, &[("i", bond.i), ("j", bond.j)], field)?;
            check_kind(what, field, bond.kind, self.bond_types.len(), "bond")?;
        }
        for (a, angle) in self.angles.iter().enumerate() {
            let what = || format!("angle {a} (ids {}, {}, {})", angle.i, angle.j, angle.k);
            let field = |name: &str| format!("angles[{a}].{name}");
            let ids = [("i", angle.i), ("j", angle.j), ("k", angle.k)];
            self.check_ids(what, &ids, field)?;
            check_kind(what, field, angle.kind, self.angle_types.len(), "angle")?;
        }
        Ok(Topology {
            particles: self.particles,
            bond_types: self.bond_types,
            bonds: self.bonds,
            angle_types: self.angle_types,
            angles: self.angles,
        })
    }

    /// Every id below the particle count and different from the ones before it.
    fn check_ids(
        &self,
        what: impl Fn() -> String,
        ids: &[(&str, u32)],
        field: impl Fn(&str) -> String,
    ) -> Result<(), ParamError> {
        for (n, &(name, id)) in ids.iter().enumerate() {
            if id as usize >= self.particles {
                return Err(ParamError::new(
                    field(name),
                    id,
                    format!(
                        "{}: ids must be < {} (the particle count)",
                        what(),
                        self.particles
                    ),
                ));
            }
            if let Some(&(other, _)) = ids[..n].iter().find(|&&(_, o)| o == id) {
                return Err(ParamError::new(
                    field(name),
                    id,
                    format!(
                        "{}: must differ from {other}, a particle cannot bond to itself",
                        what()
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// A bond or angle type below the number of types.
fn check_kind(
    what: impl Fn() -> String,
    field: impl Fn(&str) -> String,
    kind: u16,
    types: usize,
    noun: &str,
) -> Result<(), ParamError> {
    if (kind as usize) < types {
        Ok(())
    } else {
        Err(ParamError::new(
            field("kind"),
            kind,
            format!("{}: must be < {types} (the number of {noun} types)", what()),
        ))
    }
}

impl TryFrom<TopologyBuilder> for Topology {
    type Error = ParamError;
    fn try_from(b: TopologyBuilder) -> Result<Self, ParamError> {
        b.build()
    }
}

impl From<Topology> for TopologyBuilder {
    fn from(t: Topology) -> Self {
        TopologyBuilder {
            particles: t.particles,
            bond_types: t.bond_types,
            bonds: t.bonds,
            angle_types: t.angle_types,
            angles: t.angles,
        }
    }
}

impl Topology {
    /// Start a topology of `particles` particles (no types, no bonds yet).
    pub fn builder(particles: usize) -> TopologyBuilder {
        TopologyBuilder {
            particles,
            ..TopologyBuilder::default()
        }
    }
    /// The number of particles the ids refer to.
    pub fn particles(&self) -> usize {
        self.particles
    }
    pub fn bond_types(&self) -> &[BondStyle] {
        &self.bond_types
    }
    /// The bonds, by particle id, in the order given.
    pub fn bonds(&self) -> &[Bond] {
        &self.bonds
    }
    pub fn angle_types(&self) -> &[AngleStyle] {
        &self.angle_types
    }
    /// The angles, by particle id, in the order given.
    pub fn angles(&self) -> &[Angle] {
        &self.angles
    }
    /// Whether the topology has no bonded interaction (no bond and no angle).
    pub fn is_empty(&self) -> bool {
        self.bonds.is_empty() && self.angles.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chain() -> TopologyBuilder {
        TopologyBuilder {
            particles: 4,
            bond_types: vec![BondStyle::Harmonic { k: 2.0, r0: 0.0 }],
            bonds: vec![
                Bond {
                    i: 0,
                    j: 1,
                    kind: 0,
                },
                Bond {
                    i: 1,
                    j: 2,
                    kind: 0,
                },
                Bond {
                    i: 2,
                    j: 3,
                    kind: 0,
                },
            ],
            angle_types: vec![AngleStyle::Cosine { k: 1.0 }],
            angles: vec![Angle {
                i: 0,
                j: 1,
                k: 2,
                kind: 0,
            }],
        }
    }

    fn message(b: TopologyBuilder) -> String {
        b.build().unwrap_err().to_string()
    }

    #[test]
    fn a_valid_chain_builds() {
        let t = chain().build().unwrap();
        assert_eq!(t.bonds().len(), 3);
        assert_eq!(t.angles()[0].j, 1);
        assert!(!t.is_empty());
        assert!(Topology::builder(4).build().unwrap().is_empty());
    }

    #[test]
    fn errors_name_the_bond_its_ids_and_the_field() {
        let mut b = chain();
        b.bonds[2].j = 4;
        assert_eq!(
            message(b),
            "invalid bonds[2].j = 4: bond 2 (ids 2, 4): ids must be < 4 (the particle count)"
        );
        let mut b = chain();
        b.bonds[1].j = 1;
        assert_eq!(
            message(b),
            "invalid bonds[1].j = 1: bond 1 (ids 1, 1): must differ from i, a particle cannot \
             bond to itself"
        );
        let mut b = chain();
        b.bonds[0].kind = 1;
        assert_eq!(
            message(b),
            "invalid bonds[0].kind = 1: bond 0 (ids 0, 1): must be < 1 (the number of bond types)"
        );
        let mut b = chain();
        b.angles[0].k = 0;
        assert_eq!(
            message(b),
            "invalid angles[0].k = 0: angle 0 (ids 0, 1, 0): must differ from i, a particle \
             cannot bond to itself"
        );
    }

    #[test]
    fn coefficients_must_be_finite_and_positive() {
        let cases = [
            (
                BondStyle::Harmonic { k: 0.0, r0: 0.0 },
                "bond_types[0].k = 0",
            ),
            (
                BondStyle::Harmonic { k: 1.0, r0: -0.5 },
                "bond_types[0].r0 = -0.5",
            ),
            (
                BondStyle::Fene {
                    k: 30.0,
                    r_max: f64::NAN,
                },
                "bond_types[0].r_max = NaN",
            ),
        ];
        for (style, field) in cases {
            let mut b = chain();
            b.bond_types[0] = style;
            assert!(
                message(b).starts_with(&format!("invalid {field}:")),
                "{style:?}"
            );
        }
        let mut b = chain();
        b.angle_types.push(AngleStyle::CosineSquared {
            k: 1.0,
            theta0: 4.0,
        });
        assert_eq!(
            message(b),
            "invalid angle_types[1].theta0 = 4: must be in [0, pi] radians"
        );
    }

    #[test]
    fn serde_revalidates() {
        let t = chain().build().unwrap();
        let bytes = bincode::serialize(&t).unwrap();
        assert_eq!(bincode::deserialize::<Topology>(&bytes).unwrap(), t);
        let mut bad = chain();
        bad.bonds[0].i = 9;
        let bytes = bincode::serialize(&bad).unwrap();
        assert!(bincode::deserialize::<Topology>(&bytes).is_err());
    }
}
