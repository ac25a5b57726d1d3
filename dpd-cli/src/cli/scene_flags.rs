//! The flags that set scene keys: each replaces the key of the same name in the scene file (or
//! the default scene), which checks it as it checks the file's own keys.

use dpd::lang::split_schemes;
use dpd_measure::scene::section::{json_keys, merge};
use dpd_measure::{Keys, Observable, Scene, SceneError};
use serde::Serialize;
use serde_json::json;
use std::path::PathBuf;

/// The scene file and the top-level scene keys that have flags.
#[derive(Clone, Debug, Default, clap::Args, Serialize)]
pub struct SceneFlags {
    /// Scene file (TOML); default: the standard gamma = 4.5 box
    #[arg(long, value_name = "FILE")]
    #[serde(skip)]
    pub scene: Option<PathBuf>,
    /// Registry name or scheme string
    #[arg(long)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub scheme: Option<String>,
    /// Run scheme strings the order analysis finds inconsistent (coefficient sums other than 1)
    #[arg(long)]
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub allow_inconsistent: bool,
    #[arg(long, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gamma: Option<f64>,
    /// Time step
    #[arg(long, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dt: Option<f64>,
    /// Run length in time units
    #[arg(long, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub time: Option<f64>,
    /// Number of particles
    #[arg(long, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub n: Option<usize>,
    #[arg(long, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub density: Option<f64>,
    /// Conservative repulsion
    #[arg(long, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub a: Option<f64>,
    /// Target temperature k_B T
    #[arg(long, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kbt: Option<f64>,
    #[arg(long, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mass: Option<f64>,
    #[arg(long, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub weight_exponent: Option<f64>,
    /// Lowe-Andersen collision frequency Gamma (schemes with L)
    #[arg(long, value_name = "GAMMA", allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub collision_rate: Option<f64>,
    /// Mass mu of the adaptive friction factor xi, energy units (schemes with Oa and Xi)
    #[arg(long, value_name = "MU", allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub thermostat_mass: Option<f64>,
    /// Langevin friction gamma_xi of xi, per unit time (PNHL: schemes with On and Xi)
    #[arg(long, value_name = "GAMMA_XI", allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub thermostat_friction: Option<f64>,
    /// Seed of the first run
    #[arg(long, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    /// Independent runs (seeds)
    #[arg(long, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub runs: Option<u64>,
    /// Worker threads (0: one per core)
    #[arg(long, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub threads: Option<usize>,
    /// Lees-Edwards shear rate kappa (measures the shear viscosity)
    #[arg(long, value_name = "KAPPA", allow_hyphen_values = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shear_rate: Option<f64>,
    /// Measure heat and shadow work over the averaging window (schemes of A, B, O, Ob)
    #[arg(long)]
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub energy_balance: bool,
    /// Read T_C, U and the virial at the processed positions x + C dt^2 F(x) / m (one more
    /// force evaluation per sample; 0: unprocessed)
    #[arg(long, value_name = "C", allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub processing: Option<f64>,
}

/// The `[sweep]` keys that have flags.
#[derive(Clone, Debug, Default, clap::Args, Serialize)]
pub struct SweepFlags {
    /// Schemes to compare, comma-separated registry names or scheme strings (commas inside
    /// brackets or parentheses, as in `prk(b = [...], ...)`, belong to the scheme)
    #[arg(long, value_parser = scheme_list)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub schemes: Option<SchemeList>,
    /// Smallest time step of the grid
    #[arg(long, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dt_min: Option<f64>,
    /// Largest time step of the grid
    #[arg(long, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dt_max: Option<f64>,
    /// Ratio of neighbouring time steps (default 1.15)
    #[arg(long, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dt_factor: Option<f64>,
    /// Scheme whose efficiency is 1 (default: vv if swept, else the first scheme)
    #[arg(long)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reference: Option<String>,
    /// Whose relative error gives the critical dt: T_C against k_B T (default) or, in a
    /// sheared scene, the shear viscosity against the baseline run
    #[arg(long, value_parser = observable_names())]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub observable: Option<String>,
}

/// The schemes of `--schemes`: one value for clap (a `Vec` would be many), a list in the scene.
#[derive(Clone, Debug, Serialize)]
#[serde(transparent)]
pub struct SchemeList(pub Vec<String>);

fn scheme_list(text: &str) -> Result<SchemeList, String> {
    split_schemes(text).map(SchemeList)
}

fn observable_names() -> clap::builder::PossibleValuesParser {
    Observable::ALL.map(Observable::name).into()
}

/// The `[rdf]`, `[vacf]` and `[profile]` tables switched on from the command line. A flag that
/// sets a key switches its table on; keys not given keep the scene file's value, else the
/// default.
#[derive(Clone, Debug, Default, clap::Args)]
pub struct ObserveFlags {
    /// Accumulate g(r) over the averaging window (the scene's [rdf] table)
    #[arg(long)]
    pub rdf: bool,
    /// Range of g(r), at most half the box edge (default 2.5)
    #[arg(long, value_name = "R", allow_negative_numbers = true)]
    pub rdf_r_max: Option<f64>,
    /// Bins of g(r) (default 50)
    #[arg(long, value_name = "N")]
    pub rdf_bins: Option<usize>,
    /// Velocity autocorrelation, reported as the diffusion coefficient ([vacf])
    #[arg(long)]
    pub vacf: bool,
    /// Longest correlation time of the VACF (default 5)
    #[arg(long, value_name = "T", allow_negative_numbers = true)]
    pub vacf_max_lag: Option<f64>,
    /// Slab profiles of density, velocity and temperature ([profile])
    #[arg(long)]
    pub profile: bool,
    /// Axis across the slabs: 0 = x, 1 = y, 2 = z (default 2)
    #[arg(long, value_name = "AXIS")]
    pub profile_axis: Option<usize>,
    /// Slabs of the profile (default 20)
    #[arg(long, value_name = "N")]
    pub profile_bins: Option<usize>,
}

/// `value`'s fields as scene keys: `Serialize` turns a struct into a table, and no flag
/// struct holds what TOML cannot.
fn keys_of(value: &impl Serialize) -> Result<Keys, SceneError> {
    Keys::try_from(value).map_err(|e| SceneError::Toml {
        path: "(flags)".into(),
        message: e.to_string(),
    })
}

impl SceneFlags {
    /// The scene file with the flags' keys applied, validated.
    pub fn scene(&self) -> Result<Scene, SceneError> {
        self.scene_with(&Keys::new())
    }

    /// The scene file with the flags' keys and then `more` applied, validated.
    pub fn scene_with(&self, more: &Keys) -> Result<Scene, SceneError> {
        let mut keys = keys_of(self)?;
        merge(&mut keys, more);
        Scene::resolve(self.scene.as_deref(), &keys)
    }
}

impl ObserveFlags {
    /// The tables the flags switch on, with the keys they set.
    pub fn keys(&self) -> Result<Keys, SceneError> {
        let table = |on: bool, keys: serde_json::Value| {
            let set = keys
                .as_object()
                .is_some_and(|k| k.values().any(|v| !v.is_null()));
            match on || set {
                true => keys,
                false => serde_json::Value::Null,
            }
        };
        json_keys(json!({
            "rdf": table(self.rdf, json!({"r_max": self.rdf_r_max, "bins": self.rdf_bins})),
            "vacf": table(self.vacf, json!({"max_lag": self.vacf_max_lag})),
            "profile": table(
                self.profile,
                json!({"axis": self.profile_axis, "bins": self.profile_bins})
            ),
        }))
        .map_err(|message| SceneError::Toml {
            path: "(flags)".into(),
            message,
        })
    }
}

impl SweepFlags {
    /// The flags as the scene key `sweep`: a table that is there even when no flag is given,
    /// so that a scene without `[sweep]` is swept with the default table.
    pub fn keys(&self) -> Result<Keys, SceneError> {
        let mut keys = Keys::new();
        keys.insert("sweep".into(), toml::Value::Table(keys_of(self)?));
        Ok(keys)
    }
}
