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
