//! The species section: particle types (a name, a mass, a share of the particles) and the
//! coefficients of every pair of types. A scene without it has one type, the scene's `a` and
//! `mass`, and builds the same system as before species existed.

use super::check::{non_negative, positive, require};
use crate::pair_coefficients::PairCoefficients;
use dpd_core::ParamError;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Keys `[[species]]` (the types, in type-id order) and `[pairs]` (keyed `"A-B"`).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Species {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub species: Option<Vec<TypeSpec>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pairs: Option<BTreeMap<String, PairSpec>>,
}

/// One particle type: its particles are a `count`, or a `fraction` of the scene's particles
/// (every type gives the same one of the two).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TypeSpec {
    /// Letters, digits and `_`; the name in trajectories and in `[pairs]`.
    pub name: String,
    /// Mass of its particles; default the scene's `mass`.
    #[serde(default)]
    pub mass: Option<f64>,
    #[serde(default)]
    pub count: Option<usize>,
    #[serde(default)]
    pub fraction: Option<f64>,
}

/// The coefficients of one pair of types.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PairSpec {
    /// Conservative repulsion a_ij.
    pub a: f64,
    /// Friction gamma_ij; default the scene's `gamma`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gamma: Option<f64>,
    /// Cut-off r_c,ij, in (0, 1]; default 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rc: Option<f64>,
}

/// How far the fractions may sum from 1 (they are rounded to whole particles anyway).
const FRACTION_SUM_TOLERANCE: f64 = 1e-9;

impl Species {
    /// Check the types and that every pair of them has its coefficients, for a scene of
    /// `particles` particles whose scene-wide repulsion is `a` (which must keep its default
    /// when the pairs give the repulsions).
    pub fn validate(&self, particles: usize, a: f64, default_a: f64) -> Result<(), ParamError> {
        let Some(types) = &self.species else {
            if let Some(pairs) = &self.pairs {
                let keys: Vec<&str> = pairs.keys().map(String::as_str).collect();
                return Err(ParamError::new(
                    "pairs",
                    keys.join(", "),
                    "needs [[species]]: the pairs name their types",
                ));
            }
            return Ok(());
        };
        require(
            "species",
            format!("{} types", types.len()),
            (1..=usize::from(u16::MAX)).contains(&types.len()),
            "needs 1 to 65535 [[species]] entries",
        )?;
        for (k, t) in types.iter().enumerate() {
            require(
                &format!("species[{k}].name"),
                format!("{:?}", t.name),
                !t.name.is_empty() && t.name.chars().all(|c| c.is_alphanumeric() || c == '_'),
                "must be letters, digits and _ (it names the type in [pairs] as \"A-B\")",
            )?;
            if let Some(j) = types[..k].iter().position(|u| u.name == t.name) {
                return Err(ParamError::new(
                    format!("species[{k}].name"),
                    &t.name,
                    format!("is also the name of species[{j}]: names must differ"),
                ));
            }
            if let Some(m) = t.mass {
                positive(&format!("species[{k}].mass"), m)?;
            }
        }
        self.counts(particles)?;
        require(
            "a",
            a,
            a == default_a,
            "is not used with [[species]]: give each pair's a in [pairs]",
        )?;
        self.coefficients(0.0).map(|_| ())
    }

    /// The names of the types, in type-id order (none without `[[species]]`).
    pub fn names(&self) -> Vec<String> {
        let types = self.species.as_deref().unwrap_or_default();
        types.iter().map(|t| t.name.clone()).collect()
    }

    /// The particles of each type: the counts, or the fractions of `particles` rounded to
    /// whole particles by largest remainder (ties to the earlier type) so that they sum to
    /// `particles`.
    pub fn counts(&self, particles: usize) -> Result<Vec<usize>, ParamError> {
        let types = self.species.as_deref().unwrap_or_default();
        let counts: Option<Vec<usize>> = types.iter().map(|t| t.count).collect();
        let fractions: Option<Vec<f64>> = types.iter().map(|t| t.fraction).collect();
        let mixed = types
            .iter()
            .position(|t| t.count.is_some() == t.fraction.is_some());
        match (counts, fractions) {
            (Some(counts), None) => {
                let sum: usize = counts.iter().sum();
                require(
                    "species.count",
                    format!("{counts:?} (sum {sum})"),
                    sum == particles,
                    &format!(
                        "must sum to the scene's {particles} particles (n, or density x box \
                         volume): change them, or give fractions"
                    ),
                )?;
                Ok(counts)
            }
            (None, Some(fractions)) => {
                for (k, &f) in fractions.iter().enumerate() {
                    non_negative(&format!("species[{k}].fraction"), f)?;
                }
                let sum: f64 = fractions.iter().sum();
                require(
                    "species.fraction",
                    format!("{fractions:?} (sum {sum})"),
                    (sum - 1.0).abs() <= FRACTION_SUM_TOLERANCE,
                    "must sum to 1",
                )?;
                Ok(largest_remainder(&fractions, particles))
            }
            _ => {
                let k = mixed.unwrap_or(0);
                Err(ParamError::new(
                    format!("species[{k}]"),
                    &types[k].name,
                    "needs either count or fraction, and every species the same one of them",
                ))
            }
        }
    }

    /// The coefficients of every pair of types from `[pairs]`, `gamma` where a pair gives no
    /// friction and 1 where it gives no cut-off; the error names a pair given twice, a pair
    /// naming no species, a negative coefficient or the first pair without coefficients.
    pub fn coefficients(&self, gamma: f64) -> Result<PairCoefficients, ParamError> {
        let names = self.names();
        let t = names.len();
        let mut given: Vec<Vec<Option<&PairSpec>>> = vec![vec![None; t]; t];
        let empty = BTreeMap::new();
        for (key, pair) in self.pairs.as_ref().unwrap_or(&empty) {
            let (i, j) = pair_of(key, &names)?;
            if given[i][j].is_some() {
                return Err(ParamError::new(
                    format!("pairs.{key}"),
                    pair.a,
                    format!(
                        "gives the pair {}-{} a second time (the pair is unordered)",
                        names[i], names[j]
                    ),
                ));
            }
            non_negative(&format!("pairs.{key}.a"), pair.a)?;
            if let Some(g) = pair.gamma {
                non_negative(&format!("pairs.{key}.gamma"), g)?;
            }
            if let Some(rc) = pair.rc {
                require(
                    &format!("pairs.{key}.rc"),
                    rc,
                    rc > 0.0 && rc <= 1.0,
                    "must be in (0, 1]: the largest cut-off, 1, sizes the cells",
                )?;
            }
            given[i][j] = Some(pair);
            given[j][i] = Some(pair);
        }
        for i in 0..t {
            for j in i..t {
                if given[i][j].is_none() {
                    let pair = format!("{}-{}", names[i], names[j]);
                    return Err(ParamError::new(
                        format!("pairs.{pair}"),
                        "missing",
                        format!(
                            "every pair of species needs its coefficients: {pair} = {{ a = ... }}"
                        ),
                    ));
                }
            }
        }
        let matrix = |of: &dyn Fn(&PairSpec) -> f64| -> Vec<Vec<f64>> {
            given
                .iter()
                .map(|row| row.iter().map(|p| p.map_or(0.0, of)).collect())
                .collect()
        };
        Ok(PairCoefficients {
            a: matrix(&|p| p.a),
            gamma: matrix(&|p| p.gamma.unwrap_or(gamma)),
            rc: matrix(&|p| p.rc.unwrap_or(1.0)),
        })
    }

    /// The type of each particle, by id: the first `counts[0]` ids are type 0, and so on.
    pub fn kinds(&self, particles: usize) -> Result<Vec<u16>, ParamError> {
        let counts = self.counts(particles)?;
        Ok(counts
            .iter()
            .enumerate()
            .flat_map(|(t, &c)| std::iter::repeat_n(t as u16, c))
            .collect())
    }

    /// The mass of each type, `mass` where a type gives none.
    pub fn masses(&self, mass: f64) -> Vec<f64> {
        let types = self.species.as_deref().unwrap_or_default();
        types.iter().map(|t| t.mass.unwrap_or(mass)).collect()
    }
}

/// The type indices of the pair key `"A-B"`.
fn pair_of(key: &str, names: &[String]) -> Result<(usize, usize), ParamError> {
    let index = |name: &str| names.iter().position(|n| n == name);
    match key.split_once('-') {
        Some((x, y)) => match (index(x), index(y)) {
            (Some(i), Some(j)) => Ok((i, j)),
            _ => Err(ParamError::new(
                format!("pairs.{key}"),
                key,
                format!(
                    "names a species that is not in [[species]] ({})",
                    names.join(", ")
                ),
            )),
        },
        None => Err(ParamError::new(
            format!("pairs.{key}"),
            key,
            "must name two species as \"A-B\"",
        )),
    }
}

/// `fractions` of `total`, rounded down, with the remaining units given to the largest
/// remainders (ties to the earlier index): the result sums to `total`.
fn largest_remainder(fractions: &[f64], total: usize) -> Vec<usize> {
    let exact: Vec<f64> = fractions.iter().map(|f| f * total as f64).collect();
    let mut counts: Vec<usize> = exact.iter().map(|x| x.floor() as usize).collect();
    let mut order: Vec<usize> = (0..fractions.len()).collect();
    order.sort_by(|&i, &j| {
        let (ri, rj) = (exact[i] - exact[i].floor(), exact[j] - exact[j].floor());
        rj.total_cmp(&ri).then(i.cmp(&j))
    });
    let short = total.saturating_sub(counts.iter().sum());
    for &k in order.iter().cycle().take(short) {
        counts[k] += 1;
    }
    counts
}

#[cfg(test)]
mod tests {
    use super::*;

    fn species(text: &str) -> Species {
        super::super::section::take(&mut toml::from_str(text).unwrap()).unwrap()
    }

    const BINARY: &str = "[[species]]\nname = \"A\"\nfraction = 0.3\n\
                          [[species]]\nname = \"B\"\nfraction = 0.7\nmass = 2.0\n\
                          [pairs]\nA-A = { a = 25.0 }\nB-B = { a = 25.0 }\nB-A = { a = 40.0 }\n";

    #[test]
    fn types_take_their_share_mass_and_pair_coefficients() {
        let s = species(BINARY);
        s.validate(10, 25.0, 25.0).unwrap();
        assert_eq!(s.counts(10).unwrap(), [3, 7]);
        assert_eq!(s.kinds(4).unwrap(), [0, 1, 1, 1]);
        assert_eq!(s.masses(1.0), [1.0, 2.0]);
        assert_eq!(s.coefficients(4.5).unwrap().a, [[25.0, 40.0], [40.0, 25.0]]);
        assert_eq!(s.names(), ["A", "B"]);
        // A pair's own friction and cut-off; the others take the scene's gamma and 1.
        let own = species(&BINARY.replace(
            "B-A = { a = 40.0 }",
            "B-A = { a = 40.0, gamma = 9.0, rc = 0.8 }",
        ));
        let c = own.coefficients(4.5).unwrap();
        assert_eq!(c.gamma, [[4.5, 9.0], [9.0, 4.5]]);
        assert_eq!(c.rc, [[1.0, 0.8], [0.8, 1.0]]);
    }

    #[test]
    fn fractions_round_to_whole_particles_that_sum_to_the_total() {
        // 7/3 each: remainders 1/3 each, the first type takes the one left over.
        let third = 1.0 / 3.0;
        assert_eq!(largest_remainder(&[third; 3], 7), [3, 2, 2]);
        assert_eq!(largest_remainder(&[0.15, 0.85], 10), [2, 8]);
        assert_eq!(
            largest_remainder(&[0.5, 0.5], 501).iter().sum::<usize>(),
            501
        );
    }

    #[test]
    fn errors_name_the_key_and_the_pair() {
        let without = |pair: &str| BINARY.replace(pair, "");
        let counts = BINARY.replace("fraction", "count").replace("0.3", "3");
        for (text, key) in [
            (without("B-A = { a = 40.0 }\n"), "pairs.A-B"),
            (BINARY.replace("B-A", "A-C"), "pairs.A-C"),
            (BINARY.replace("B-B", "A-B"), "pairs.B-A"),
            (BINARY.replace("A-A", "AA"), "pairs.AA"),
            (BINARY.replace("a = 40.0", "a = -1.0"), "pairs.B-A.a"),
            (
                BINARY.replace("a = 40.0", "a = 40.0, gamma = -1.0"),
                "pairs.B-A.gamma",
            ),
            (
                BINARY.replace("a = 40.0", "a = 40.0, rc = 1.5"),
                "pairs.B-A.rc",
            ),
            (BINARY.replace("0.7", "0.6"), "species.fraction"),
            (BINARY.replace("fraction = 0.7", "count = 7"), "species[0]"),
            (counts.replace("0.7", "6"), "species.count"),
            (
                BINARY.replace("mass = 2.0", "mass = 0.0"),
                "species[1].mass",
            ),
            (BINARY.replace("\"B\"", "\"A\""), "species[1].name"),
            (BINARY.replace("\"B\"", "\"B-1\""), "species[1].name"),
        ] {
            let e = species(&text).validate(10, 25.0, 25.0).unwrap_err();
            assert_eq!(e.field, key, "{text}: {e}");
        }
        let e = species(BINARY).validate(10, 30.0, 25.0).unwrap_err();
        assert_eq!(e.field, "a");
        let e = species("[pairs]\nA-A = { a = 25.0 }").validate(10, 25.0, 25.0);
        assert_eq!(e.unwrap_err().field, "pairs");
        let missing = species(&without("B-A = { a = 40.0 }\n"));
        let e = missing.validate(10, 25.0, 25.0).unwrap_err().to_string();
        assert!(e.contains("A-B = { a = ... }"), "{e}");
    }
}
