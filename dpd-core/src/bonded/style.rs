//! Bond and angle styles: the potential of one bond or one angle, in LAMMPS's conventions so
//! that a LAMMPS data file's `Bond Coeffs` and `Angle Coeffs` mean the same system here.

use crate::error::{positive, ParamError};
use serde::{Deserialize, Serialize};

/// The potential of a bond of length `r` (length units; energies in k_B T's unit).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum BondStyle {
    /// `E = K (r - r0)^2` (LAMMPS `bond_style harmonic`: no factor 1/2, so the force constant
    /// is `2K`). `K > 0` (energy / length^2), `r0 >= 0` (length). Groot and Warren's chains
    /// (spring force `-C r` with `C = 4`, energy `C r^2 / 2`) are `K = 2, r0 = 0`.
    Harmonic { k: f64, r0: f64 },
    /// `E = -K R0^2 / 2 ln(1 - (r / R0)^2)` for `r < R0` (LAMMPS `bond_style fene` with
    /// `epsilon = 0`): the finitely extensible spring alone, without the WCA repulsion of
    /// Kremer-Grest chains, because DPD beads keep their soft repulsion, which already keeps
    /// bonded beads apart. `K > 0` (energy / length^2), `R0 > 0` (length); a bond reaching
    /// `R0` is a blow-up.
    Fene { k: f64, r_max: f64 },
}

/// The potential of an angle `theta` at its vertex bead `j` between the bonds to `i` and `k`
/// (`theta = pi` for a straight chain; energies in k_B T's unit).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum AngleStyle {
    /// `E = K (1 + cos theta)` (LAMMPS `angle_style cosine`), least for a straight chain.
    /// `K > 0` (energy).
    Cosine { k: f64 },
    /// `E = K (cos theta - cos theta0)^2` (LAMMPS `angle_style cosine/squared`, no factor 1/2).
    /// `K > 0` (energy); `theta0` in radians, in `[0, pi]` (LAMMPS's `Angle Coeffs` give it in
    /// degrees).
    CosineSquared { k: f64, theta0: f64 },
}

/// In LAMMPS's words: `harmonic (K = 100, r0 = 0.7)`, `fene (K = 30, R0 = 1.5)`.
impl std::fmt::Display for BondStyle {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            BondStyle::Harmonic { k, r0 } => write!(f, "harmonic (K = {k}, r0 = {r0})"),
            BondStyle::Fene { k, r_max } => write!(f, "fene (K = {k}, R0 = {r_max})"),
        }
    }
}

impl BondStyle {
    /// Check the coefficients; `field` names the bond type, e.g. `bond_types[1]`.
    pub(crate) fn check(&self, field: &str) -> Result<(), ParamError> {
        match *self {
            BondStyle::Harmonic { k, r0 } => {
                positive(&format!("{field}.k"), k)?;
                if !(r0.is_finite() && r0 >= 0.0) {
                    return Err(ParamError::new(
                        format!("{field}.r0"),
                        r0,
                        "must be finite and >= 0",
                    ));
                }
            }
            BondStyle::Fene { k, r_max } => {
                positive(&format!("{field}.k"), k)?;
                positive(&format!("{field}.r_max"), r_max)?;
            }
        }
        Ok(())
    }
}

impl AngleStyle {
    /// Check the coefficients; `field` names the angle type, e.g. `angle_types[0]`.
    pub(crate) fn check(&self, field: &str) -> Result<(), ParamError> {
        match *self {
            AngleStyle::Cosine { k } => {
                positive(&format!("{field}.k"), k)?;
            }
            AngleStyle::CosineSquared { k, theta0 } => {
                positive(&format!("{field}.k"), k)?;
                if !(theta0.is_finite() && (0.0..=std::f64::consts::PI).contains(&theta0)) {
                    return Err(ParamError::new(
                        format!("{field}.theta0"),
                        theta0,
                        "must be in [0, pi] radians",
                    ));
                }
            }
        }
        Ok(())
    }
}

impl BondStyle {
    /// The energy at length `r`.
    #[inline]
    pub fn energy(&self, r: f64) -> f64 {
        match *self {
            BondStyle::Harmonic { k, r0 } => k * (r - r0) * (r - r0),
            BondStyle::Fene { k, r_max } => {
                -0.5 * k * r_max * r_max * (1.0 - (r * r) / (r_max * r_max)).ln()
            }
        }
    }

    /// `-E'(r) / r` at squared length `r2`: the force on `i` is this times `q_i - q_j`.
    /// Harmonic: `-2K (r - r0) / r` (`-2K` when `r0 = 0`, also at `r = 0`); FENE: `-K / (1 -
    /// r^2/R0^2)`, meaningless once `r >= R0` ([`Self::overstretched`]).
    #[inline]
    pub fn force_over_r(&self, r2: f64) -> f64 {
        match *self {
            BondStyle::Harmonic { k, r0: 0.0 } => -2.0 * k,
            BondStyle::Harmonic { k, r0 } => {
                let r = r2.sqrt();
                -2.0 * k * (r - r0) / r
            }
            BondStyle::Fene { k, r_max } => -k / (1.0 - r2 / (r_max * r_max)),
        }
    }

    /// `E''(r)` at squared length `r2`. Harmonic: `2K`; FENE: `K / (1 - x) + 2K x / (1 - x)^2`
    /// with `x = r^2 / R0^2`.
    #[inline]
    pub fn curvature(&self, r2: f64) -> f64 {
        match *self {
            BondStyle::Harmonic { k, .. } => 2.0 * k,
            BondStyle::Fene { k, r_max } => {
                let x = r2 / (r_max * r_max);
                k / (1.0 - x) + 2.0 * k * x / ((1.0 - x) * (1.0 - x))
            }
        }
    }

    /// Both particles' Laplacians of the bond energy at squared length `r2`: in three
    /// dimensions `lap E = E'' + 2 E' / r` for each, so `2 (E'' + 2 E' / r)`. Harmonic with `r0
    /// = 0`: `2 * 3 * 2K = 12 K`; harmonic: `4K (1 + 2 (r - r0) / r)`; FENE: `2 (3K / (1 - x) +
    /// 2K x / (1 - x)^2)`.
    #[inline]
    pub fn laplacian(&self, r2: f64) -> f64 {
        2.0 * (self.curvature(r2) - 2.0 * self.force_over_r(r2))
    }

    /// Whether a bond of squared length `r2` is beyond the style's reach: a FENE bond at or
    /// past `R0` (or a non-finite length).
    #[inline]
    pub(crate) fn overstretched(&self, r2: f64) -> bool {
        match *self {
            BondStyle::Harmonic { .. } => !r2.is_finite(),
            BondStyle::Fene { r_max, .. } => r2 >= r_max * r_max || r2.is_nan(),
        }
    }
}

impl AngleStyle {
    /// The energy at `c = cos theta`.
    #[inline]
    pub fn energy(&self, c: f64) -> f64 {
        match *self {
            AngleStyle::Cosine { k } => k * (1.0 + c),
            AngleStyle::CosineSquared { k, theta0 } => {
                let d = c - theta0.cos();
                k * d * d
            }
        }
    }

    /// `d^2 E / d cos theta^2` at `c = cos theta`.
    #[inline]
    pub fn curvature(&self, _c: f64) -> f64 {
        match *self {
            AngleStyle::Cosine { .. } => 0.0,
            AngleStyle::CosineSquared { k, .. } => 2.0 * k,
        }
    }

    /// `dE / d cos theta` at `c = cos theta`.
    #[inline]
    pub fn slope(&self, c: f64) -> f64 {
        match *self {
            AngleStyle::Cosine { k } => k,
            AngleStyle::CosineSquared { k, theta0 } => 2.0 * k * (c - theta0.cos()),
        }
    }
}
