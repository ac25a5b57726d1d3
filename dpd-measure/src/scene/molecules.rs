//! The molecules section: bond and angle types in LAMMPS's conventions, and linear chains of
//! beads, each chain a run of consecutive particle ids bonded neighbour to neighbour. A scene
//! without it has no bonds and builds the same system as before molecules existed.

use super::check::{positive, require};
use dpd_core::bonded::{AngleStyle, BondStyle};
use dpd_core::ParamError;
use serde::{Deserialize, Serialize};

/// Keys `[[bond_types]]`, `[[angle_types]]` and `[[molecules]]` (in type-id order each), and
/// `exclude_bonded`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Molecules {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bond_types: Option<Vec<BondType>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub angle_types: Option<Vec<AngleType>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub molecules: Option<Vec<ChainSpec>>,
    /// Leave bonded pairs out of the pair forces, as LAMMPS's `special_bonds lj 0 1 1` with
    /// pair dpd (default: bonded beads keep their soft repulsion, `special_bonds lj 1 1 1`).
    /// Needs bonds, from `[[molecules]]` or the `init` data file.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub exclude_bonded: bool,
}

/// A bond type: `style = "harmonic"`, `E = k (r - r0)^2` (no 1/2, as LAMMPS), or `"fene"`,
/// `E = -k r_max^2 / 2 ln(1 - (r / r_max)^2)` (LAMMPS's fene without its WCA core).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BondType {
    pub name: String,
    pub style: String,
    /// Energy / length^2.
    pub k: f64,
    /// Harmonic rest length (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub r0: Option<f64>,
    /// FENE's largest extension.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub r_max: Option<f64>,
}

/// An angle type: `style = "cosine"`, `E = k (1 + cos theta)`, or `"cosine_squared"`,
/// `E = k (cos theta - cos theta0)^2`, theta at the middle bead (180 degrees: straight).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AngleType {
    pub name: String,
    pub style: String,
    /// Energy.
    pub k: f64,
    /// cosine_squared's rest angle in degrees (as LAMMPS's Angle Coeffs), in [0, 180].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub theta0: Option<f64>,
}

/// Linear chains of `length` beads: `count` chains, or as many as hold the `fraction` of the
/// scene's particles (rounded, at least one).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChainSpec {
    pub length: usize,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub count: Option<usize>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fraction: Option<f64>,
    /// The species of each bead along the chain, names separated by spaces ("A A B B"), or one
    /// name for all; default the first species.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub beads: Option<String>,
    /// The bond type between neighbours.
    pub bond: String,
    /// The angle type at every inner bead; default none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub angle: Option<String>,
    /// Step length of the random walks that place the chains; default the bond's typical
    /// length ([`typical_length`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub step: Option<f64>,
}

/// What the scene's checks need from the other sections.
pub struct Context<'a> {
    /// Species names in type order (`["A"]` without species).
    pub species: &'a [String],
    /// Particles of each species (the scene's particle count without species).
    pub counts: &'a [usize],
    pub kbt: f64,
    /// The shortest box edge.
    pub shortest_edge: f64,
}

/// One chain entry resolved: its chains, bead types, bond and angle type indices, step.
#[derive(Clone, Debug, PartialEq)]
pub struct ChainPlan {
    pub chains: usize,
    pub beads: Vec<u16>,
    pub bond: u16,
    pub angle: Option<u16>,
    pub step: f64,
}

/// A random-walk step is shorter than this share of the box's shortest edge, so that minimum
/// image recovers every bond.
const STEP_LIMIT: f64 = 0.5;

impl BondType {
    /// The potential; the error names the key of `bond_types[index]` that is wrong.
    pub fn style(&self, index: usize) -> Result<BondStyle, ParamError> {
        let key = |k: &str| format!("bond_types[{index}].{k}");
        positive(&key("k"), self.k)?;
        let (k, style) = (self.k, self.style.as_str());
        let absent = |name: &str, v: Option<f64>| {
            let allowed = format!("is not a key of style {style:?}");
            require(&key(name), v.unwrap_or_default(), v.is_none(), &allowed)
        };
        match style {
            "harmonic" => {
                absent("r_max", self.r_max)?;
                let r0 = self.r0.unwrap_or(0.0);
                let ok = r0.is_finite() && r0 >= 0.0;
                require(&key("r0"), r0, ok, "must be finite and >= 0")?;
                Ok(BondStyle::Harmonic { k, r0 })
            }
            "fene" => {
                absent("r0", self.r0)?;
                let r_max = self.r_max.ok_or_else(|| {
                    ParamError::new(key("r_max"), "missing", "style \"fene\" needs r_max")
                })?;
                positive(&key("r_max"), r_max)?;
                Ok(BondStyle::Fene { k, r_max })
            }
            _ => Err(ParamError::new(
                key("style"),
                format!("{style:?}"),
                "must be \"harmonic\" or \"fene\"",
            )),
        }
    }
}

/// The typical length of a bond of `style` at `kbt`: `r0` of a harmonic bond with `r0 > 0`;
/// otherwise the root-mean-square length of the spring alone near r = 0, `sqrt(3 kbt / (2 k))`
/// for the harmonic `k r^2` and `sqrt(3 kbt / k)` for FENE's `k r^2 / 2`, the latter at most
/// `r_max / 2`.
pub fn typical_length(style: BondStyle, kbt: f64) -> f64 {
    match style {
        BondStyle::Harmonic { r0, .. } if r0 > 0.0 => r0,
        BondStyle::Harmonic { k, .. } => (1.5 * kbt / k).sqrt(),
        BondStyle::Fene { k, r_max } => (3.0 * kbt / k).sqrt().min(0.5 * r_max),
    }
}

impl AngleType {
    /// The potential; the error names the key of `angle_types[index]` that is wrong.
    pub fn style(&self, index: usize) -> Result<AngleStyle, ParamError> {
        let key = |k: &str| format!("angle_types[{index}].{k}");
        positive(&key("k"), self.k)?;
        match self.style.as_str() {
            "cosine" => {
                let v = self.theta0.unwrap_or_default();
                let allowed = "is not a key of style \"cosine\"";
                require(&key("theta0"), v, self.theta0.is_none(), allowed)?;
                Ok(AngleStyle::Cosine { k: self.k })
            }
            "cosine_squared" => {
                let theta0 = self.theta0.ok_or_else(|| {
                    let why = "style \"cosine_squared\" needs theta0 (degrees)";
                    ParamError::new(key("theta0"), "missing", why)
                })?;
                let ok = (0.0..=180.0).contains(&theta0);
                require(&key("theta0"), theta0, ok, "must be in [0, 180] degrees")?;
                let theta0 = theta0.to_radians();
                Ok(AngleStyle::CosineSquared { k: self.k, theta0 })
            }
            style => Err(ParamError::new(
                key("style"),
                format!("{style:?}"),
                "must be \"cosine\" or \"cosine_squared\"",
            )),
        }
    }
}

impl Molecules {
    /// `exclude_bonded` only where there are bonds (`bonded`).
    pub fn check_exclusion(&self, bonded: bool) -> Result<(), ParamError> {
        let why = "needs bonds: give [[molecules]], or an init data file with Bonds";
        require("exclude_bonded", true, !self.exclude_bonded || bonded, why)
    }

    /// Whether the scene has chains.
    pub fn any(&self) -> bool {
        self.molecules.as_ref().is_some_and(|m| !m.is_empty())
    }

    /// The bond potentials in type order.
    pub fn bond_styles(&self) -> Result<Vec<BondStyle>, ParamError> {
        let types = self.bond_types.as_deref().unwrap_or_default();
        types.iter().enumerate().map(|(i, t)| t.style(i)).collect()
    }

    /// The angle potentials in type order.
    pub fn angle_styles(&self) -> Result<Vec<AngleStyle>, ParamError> {
        let types = self.angle_types.as_deref().unwrap_or_default();
        types.iter().enumerate().map(|(i, t)| t.style(i)).collect()
    }

    /// Check every key and resolve the chains for a scene of `particles` particles; the
    /// error names the key, its value and what is valid.
    pub fn plan(&self, particles: usize, cx: &Context) -> Result<Vec<ChainPlan>, ParamError> {
        let bonds = self.bond_styles()?;
        self.angle_styles()?;
        let bond_names = names(
            "bond_types",
            self.bond_types.iter().flatten().map(|t| &t.name),
        )?;
        let angle_names = names(
            "angle_types",
            self.angle_types.iter().flatten().map(|t| &t.name),
        )?;
        let mut plans = Vec::new();
        for (m, spec) in self.molecules.iter().flatten().enumerate() {
            let key = |k: &str| format!("molecules[{m}].{k}");
            let length = spec.length;
            let ok = (2..=particles).contains(&length);
            let allowed = format!("must be 2 to the scene's {particles} particles");
            require(&key("length"), length, ok, &allowed)?;
            let chains = match (spec.count, spec.fraction) {
                (Some(c), None) => {
                    require(&key("count"), c, c >= 1, "must be at least 1")?;
                    c
                }
                (None, Some(f)) => {
                    let ok = f.is_finite() && f > 0.0 && f <= 1.0;
                    require(&key("fraction"), f, ok, "must be in (0, 1]")?;
                    ((f * particles as f64 / length as f64).round() as usize).max(1)
                }
                _ => {
                    return Err(ParamError::new(
                        format!("molecules[{m}]"),
                        format!("{length}-bead chains"),
                        "needs either count (chains) or fraction (of the particles)",
                    ))
                }
            };
            let beads = bead_types(spec, &key("beads"), cx.species)?;
            let bond = index_of(&bond_names, &spec.bond, &key("bond"), "[[bond_types]]")?;
            let angle = match &spec.angle {
                Some(a) => {
                    let why = "needs chains of at least 3 beads";
                    require(&key("angle"), a, length >= 3, why)?;
                    Some(index_of(&angle_names, a, &key("angle"), "[[angle_types]]")?)
                }
                None => None,
            };
            let kind = bonds[bond as usize];
            let step = spec.step.unwrap_or(typical_length(kind, cx.kbt));
            check_step(&key("step"), step, kind, cx.shortest_edge)?;
            plans.push(ChainPlan {
                chains,
                beads,
                bond,
                angle,
                step,
            });
        }
        check_beads(&plans, particles, cx)?;
        Ok(plans)
    }
}

/// The names of a `[[table]]`'s entries, which must be distinct and letters, digits and `_`.
fn names<'a>(
    table: &str,
    entries: impl Iterator<Item = &'a String>,
) -> Result<Vec<&'a String>, ParamError> {
    let mut seen: Vec<&String> = Vec::new();
    for (i, name) in entries.enumerate() {
        let key = format!("{table}[{i}].name");
        let ok = !name.is_empty() && name.chars().all(|c| c.is_alphanumeric() || c == '_');
        require(
            &key,
            format!("{name:?}"),
            ok,
            "must be letters, digits and _",
        )?;
        if let Some(j) = seen.iter().position(|s| *s == name) {
            let why = format!("is also the name of {table}[{j}]: names must differ");
            return Err(ParamError::new(key, name, why));
        }
        seen.push(name);
    }
    Ok(seen)
}

/// The index of `name` among `names`; the error names `key` and the `table` to look in.
fn index_of(names: &[&String], name: &str, key: &str, table: &str) -> Result<u16, ParamError> {
    match names.iter().position(|n| *n == name) {
        Some(i) => Ok(i as u16),
        None => {
            let known: Vec<&str> = names.iter().map(|n| n.as_str()).collect();
            let why = format!("names no entry of {table} ({})", known.join(", "));
            Err(ParamError::new(key, name, why))
        }
    }
}

/// The species of each bead of a chain: one name for all, or one per bead.
fn bead_types(spec: &ChainSpec, key: &str, species: &[String]) -> Result<Vec<u16>, ParamError> {
    let text = spec.beads.clone().unwrap_or_else(|| species[0].clone());
    let words: Vec<&str> = text.split_whitespace().collect();
    let count = words.len();
    let ok = count == 1 || count == spec.length;
    let why = format!("must name one species, or one per bead ({})", spec.length);
    require(key, format!("{text:?}"), ok, &why)?;
    let one = |w: &str| {
        let names: Vec<&String> = species.iter().collect();
        index_of(&names, w, key, "[[species]]")
    };
    let types: Vec<u16> = words.iter().map(|w| one(w)).collect::<Result<_, _>>()?;
    Ok(match types.as_slice() {
        [t] => vec![*t; spec.length],
        _ => types,
    })
}

/// A random-walk step must be positive, shorter than a FENE bond's `r_max` (or the first step
/// blows up) and than half the box's shortest edge (or minimum image loses the bond).
fn check_step(key: &str, step: f64, kind: BondStyle, edge: f64) -> Result<(), ParamError> {
    positive(key, step)?;
    if let BondStyle::Fene { r_max, .. } = kind {
        let why = format!("must be < the FENE bond's r_max = {r_max}: a longer bond blows up");
        require(key, step, step < r_max, &why)?;
    }
    let limit = STEP_LIMIT * edge;
    let why = format!("must be < half the shortest box edge, {limit}");
    require(key, step, step < limit, &why)
}

/// The chains' beads fit in the scene, and each species has the beads its chains use.
fn check_beads(plans: &[ChainPlan], particles: usize, cx: &Context) -> Result<(), ParamError> {
    let mut used = vec![0usize; cx.species.len()];
    for p in plans {
        for &t in &p.beads {
            used[t as usize] += p.chains;
        }
    }
    let total: usize = used.iter().sum();
    let why = format!("must fit in the scene's {particles} particles");
    require(
        "molecules",
        format!("{total} beads"),
        total <= particles,
        &why,
    )?;
    for ((name, &u), &have) in cx.species.iter().zip(&used).zip(cx.counts) {
        let why = format!("species {name} has {have} particles, the chains' beads need {u}");
        require("molecules", format!("{u} beads of {name}"), u <= have, &why)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests;
