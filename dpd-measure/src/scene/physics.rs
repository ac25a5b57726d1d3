//! The physics section: the pair forces, the particles' mass, and what drives the fluid out of
//! equilibrium (shear, body force).

use super::check::{non_negative, positive, require};
use dpd_core::params::ParamsBuilder;
use dpd_core::{ParamError, Params};
use serde::{Deserialize, Serialize};

/// Keys `a`, `gamma`, `kbt`, `mass`, `weight_exponent`, `collision_rate`, `thermostat_mass`,
/// `thermostat_friction`, `shear_rate`, `body_force`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Physics {
    /// Conservative repulsion a.
    pub a: f64,
    /// Dissipation strength gamma; sigma = sqrt(2 gamma k_B T).
    pub gamma: f64,
    /// Target temperature k_B T.
    pub kbt: f64,
    /// Mass of every particle.
    pub mass: f64,
    /// Weight exponent s: w_D = (1 - r)^s, w_R = (1 - r)^(s/2).
    pub weight_exponent: f64,
    /// Lowe-Andersen collision frequency Gamma per pair (per unit time), for schemes with L.
    pub collision_rate: Option<f64>,
    /// Mass mu of PAdL's adaptive friction factor xi (energy units), for schemes with Oa and
    /// Xi: xi fluctuates around 1 with variance kbt / mu.
    pub thermostat_mass: Option<f64>,
    /// Friction gamma_xi of the Langevin dynamics of xi (per unit time), for PNHL's schemes
    /// with On and Xi: xi fluctuates around 0 with variance kbt / mu.
    pub thermostat_friction: Option<f64>,
    /// Lees-Edwards shear rate kappa (x-velocity gradient along y); a non-zero rate measures
    /// the shear viscosity.
    pub shear_rate: Option<f64>,
    /// Force along x on every fluid particle (Poiseuille flow).
    pub body_force: Option<f64>,
}

impl Default for Physics {
    /// The standard box of algorithms.md section 8: a = 25, gamma = 4.5, k_B T = 1, m = 1,
    /// s = 2, at equilibrium.
    fn default() -> Self {
        Physics {
            a: 25.0,
            gamma: 4.5,
            kbt: 1.0,
            mass: 1.0,
            weight_exponent: 2.0,
            collision_rate: None,
            thermostat_mass: None,
            thermostat_friction: None,
            shear_rate: None,
            body_force: None,
        }
    }
}

impl Physics {
    pub fn validate(&self) -> Result<(), ParamError> {
        for (key, v) in [
            ("kbt", self.kbt),
            ("mass", self.mass),
            ("weight_exponent", self.weight_exponent),
        ] {
            positive(key, v)?;
        }
        non_negative("a", self.a)?;
        non_negative("gamma", self.gamma)?;
        if let Some(rate) = self.collision_rate {
            positive("collision_rate", rate)?;
        }
        if let Some(mu) = self.thermostat_mass {
            positive("thermostat_mass", mu)?;
        }
        if let Some(gamma_xi) = self.thermostat_friction {
            positive("thermostat_friction", gamma_xi)?;
        }
        if let Some(k) = self.shear_rate {
            require("shear_rate", k, k.is_finite(), "must be finite")?;
        }
        if let Some(g) = self.body_force {
            require("body_force", g, g.is_finite(), "must be finite")?;
        }
        Ok(())
    }

    /// The pair-force parameters of one particle type.
    pub fn params(&self) -> Result<Params, ParamError> {
        self.builder().build()
    }

    /// The pair-force parameters of one particle type, unvalidated.
    pub fn builder(&self) -> ParamsBuilder {
        ParamsBuilder {
            collision_rate: self.collision_rate,
            thermostat_mass: self.thermostat_mass,
            thermostat_friction: self.thermostat_friction,
            ..Params::builder()
                .a(self.a)
                .gamma(self.gamma)
                .kbt(self.kbt)
                .weight_exponent(self.weight_exponent)
        }
    }

    /// Whether the scene is sheared at a non-zero rate (and so measures the viscosity).
    pub fn sheared(&self) -> bool {
        self.shear_rate.is_some_and(|k| k != 0.0)
    }
}
