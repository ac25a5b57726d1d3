//! Scenes: what to simulate and how long, read from TOML, overridden from the command line and
//! validated with messages that name the key.
//!
//! A scene names only what it needs; every key has the default of the standard equilibrium box
//! of algorithms.md section 8 (N = 500, density 3, a = 25, gamma = 4.5, k_B T = 1, m = 1,
//! s = 2, 1000 time units averaged over the last 80 %). The optional tables `[rdf]`, `[vacf]`,
//! `[sweep]`, `[walls]` and `[profile]` and the keys `box`, `shear_rate` and `body_force`
//! switch on what they describe (see [`super::flows`]); a scene without them does not pay for
//! them.

use super::flows::{ProfileSpec, WallSpec};
use super::trajectory::{initial_state, InitSpec, TrajectorySpec};
use dpd_core::init::{cubic_box, freeze_outside, maxwell_momenta, uniform_positions};
use dpd_core::system::DEFAULT_SKIN;
use dpd_core::{ParamError, Params, PeriodicBox, System, Vec3};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use thiserror::Error;

/// One simulation set-up. Lengths in units of r_c = 1, times in reduced time units.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Scene {
    /// Free text shown in the header.
    pub description: String,
    /// Registry name or scheme string, for `dpd run`.
    pub scheme: String,
    /// Number of particles in the cubic periodic box.
    pub n: usize,
    /// Number density.
    pub density: f64,
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
    /// Time step of `dpd run`.
    pub dt: f64,
    /// Length of each run in time units; steps = round(time / dt).
    pub time: f64,
    /// Observables are averaged over this last fraction of each run; the rest equilibrates.
    pub average_fraction: f64,
    /// Time between samples; a sample is taken every max(1, round(sample_interval / dt))
    /// steps, at the end of a full step.
    pub sample_interval: f64,
    /// Seed of the first run; run k uses seed + k.
    pub seed: u64,
    /// Independent runs (seeds) per scheme and dt.
    pub runs: u64,
    /// Worker threads for independent runs; 0 means one per core.
    pub threads: usize,
    /// Verlet-list skin in units of r_c: pairs within r_c + skin are listed, and the list is
    /// rebuilt once a particle may have crossed it. 0 (the default) rebuilds the cell lists
    /// every step. It changes the cost and the order of the pair sweeps, not the physics.
    pub skin: f64,
    pub rdf: Option<RdfSpec>,
    pub vacf: Option<VacfSpec>,
    pub sweep: Option<SweepSpec>,
    /// Box edges `[L_x, L_y, L_z]`; then `n` is ignored and the box holds
    /// `round(density V)` particles (wall slabs included). Default: the cube of `n` particles.
    #[serde(rename = "box")]
    pub box_lengths: Option<[f64; 3]>,
    /// Lees-Edwards shear rate kappa (x-velocity gradient along y); a non-zero rate measures
    /// the shear viscosity.
    pub shear_rate: Option<f64>,
    /// Force along x on every fluid particle (Poiseuille flow).
    pub body_force: Option<f64>,
    pub walls: Option<WallSpec>,
    pub profile: Option<ProfileSpec>,
    pub trajectory: Option<TrajectorySpec>,
    /// Start from a frame of a GSD file, `"FILE.gsd"` (its last frame) or `"FILE.gsd:K"`.
    pub init: Option<String>,
    /// Measure the heat and the shadow work over the averaging window (schemes made of A, B,
    /// O and Ob, at equilibrium; see `dpd_core::observe::EnergyBalance`).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub energy_balance: bool,
}

/// Radial distribution function accumulated over the averaging window.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RdfSpec {
    /// Histogram range; at most half the box edge.
    pub r_max: f64,
    pub bins: usize,
    /// Time between g(r) records: every k-th sample of the averaging window, from its first,
    /// with k = max(1, round(interval / (sample steps x dt))); default every sample. A record
    /// costs an O(N^2) pass in boxes under 3 r_max, several times a step; runs that want
    /// g(r) only to draw it can record it less often than they sample T_C.
    pub interval: Option<f64>,
}

/// Velocity autocorrelation over the averaging window, reported as the diffusion coefficient.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct VacfSpec {
    /// Longest correlation time, in time units.
    pub max_lag: f64,
    /// A new time origin every this many samples.
    pub origin_every: u64,
}

/// A sweep of schemes over a geometric grid of time steps (algorithms.md section 7).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SweepSpec {
    pub schemes: Vec<String>,
    pub dt_min: f64,
    pub dt_max: f64,
    /// Ratio of neighbouring grid points; dt_k = dt_min dt_factor^k <= dt_max.
    pub dt_factor: f64,
    /// Efficiencies are scaled so that this scheme's is 1.
    pub reference: String,
    /// Scheme of the small-dt run that the potential energy and pressure are compared with.
    pub baseline_scheme: String,
    /// Time step of that run (default: dt_min).
    pub baseline_dt: Option<f64>,
    /// Whose relative error decides the critical step sizes.
    pub observable: Observable,
}

/// The accuracy measure of a sweep (algorithms.md sections 6 and 7).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum Observable {
    /// (T_C - k_B T) / k_B T.
    #[default]
    ConfigurationalTemperature,
    /// The shear viscosity relative to the baseline run's (needs a non-zero `shear_rate`).
    Viscosity,
}

impl Observable {
    /// The name used in scenes, flags and JSON.
    pub fn name(self) -> &'static str {
        match self {
            Observable::ConfigurationalTemperature => "configurational-temperature",
            Observable::Viscosity => "viscosity",
        }
    }
}

impl Default for Scene {
    fn default() -> Self {
        Scene {
            description: String::new(),
            scheme: "aboba".into(),
            n: 500,
            density: 3.0,
            a: 25.0,
            gamma: 4.5,
            kbt: 1.0,
            mass: 1.0,
            weight_exponent: 2.0,
            dt: 0.05,
            time: 1000.0,
            average_fraction: 0.8,
            sample_interval: 0.1,
            seed: 1,
            runs: 1,
            threads: 0,
            skin: DEFAULT_SKIN,
            rdf: None,
            vacf: None,
            sweep: None,
            box_lengths: None,
            shear_rate: None,
            body_force: None,
            walls: None,
            profile: None,
            trajectory: None,
            init: None,
            energy_balance: false,
        }
    }
}

impl Default for RdfSpec {
    fn default() -> Self {
        RdfSpec {
            r_max: 2.5,
            bins: 50,
            interval: None,
        }
    }
}

impl Default for VacfSpec {
    fn default() -> Self {
        VacfSpec {
            max_lag: 5.0,
            origin_every: 10,
        }
    }
}

impl Default for SweepSpec {
    fn default() -> Self {
        SweepSpec {
            schemes: vec!["vv".into(), "dpd-s1".into(), "aboba".into()],
            dt_min: 0.01,
            dt_max: 0.2,
            dt_factor: 1.15,
            reference: "vv".into(),
            baseline_scheme: "aboba".into(),
            baseline_dt: None,
            observable: Observable::default(),
        }
    }
}

/// A scene that cannot be read or is not valid.
#[derive(Debug, Error)]
pub enum SceneError {
    #[error("scene {path}: {source}")]
    Io {
        path: String,
        #[source]
        source: std::io::Error,
    },
    #[error("scene {path}: {message}")]
    Toml { path: String, message: String },
    #[error("scene: {0}")]
    Invalid(#[from] ParamError),
}

/// Command-line overrides of scene keys; each flag replaces the key of the same name. Also read
/// from keyword arguments (the Python module), where unknown keys are refused.
#[derive(Clone, Debug, Default, clap::Args, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Overrides {
    /// Scene file (TOML); default: the standard gamma = 4.5 box
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
    /// Registry name or scheme string
    #[arg(long)]
    pub scheme: Option<String>,
    #[arg(long, allow_negative_numbers = true)]
    pub gamma: Option<f64>,
    /// Time step
    #[arg(long, allow_negative_numbers = true)]
    pub dt: Option<f64>,
    /// Run length in time units
    #[arg(long, allow_negative_numbers = true)]
    pub time: Option<f64>,
    /// Number of particles
    #[arg(long, allow_negative_numbers = true)]
    pub n: Option<usize>,
    #[arg(long, allow_negative_numbers = true)]
    pub density: Option<f64>,
    /// Conservative repulsion
    #[arg(long, allow_negative_numbers = true)]
    pub a: Option<f64>,
    /// Target temperature k_B T
    #[arg(long, allow_negative_numbers = true)]
    pub kbt: Option<f64>,
    #[arg(long, allow_negative_numbers = true)]
    pub mass: Option<f64>,
    #[arg(long, allow_negative_numbers = true)]
    pub weight_exponent: Option<f64>,
    /// Seed of the first run
    #[arg(long, allow_negative_numbers = true)]
    pub seed: Option<u64>,
    /// Independent runs (seeds)
    #[arg(long, allow_negative_numbers = true)]
    pub runs: Option<u64>,
    /// Worker threads (0: one per core)
    #[arg(long, allow_negative_numbers = true)]
    pub threads: Option<usize>,
    /// Lees-Edwards shear rate kappa (measures the shear viscosity)
    #[arg(long, value_name = "KAPPA", allow_hyphen_values = true)]
    pub shear_rate: Option<f64>,
    /// Measure heat and shadow work over the averaging window (schemes of A, B, O, Ob)
    #[arg(long)]
    #[serde(default)]
    pub energy_balance: bool,
}

/// Command-line overrides of the `[sweep]` table's keys; each flag replaces the key of the same
/// name.
#[derive(Clone, Debug, Default, clap::Args)]
pub struct SweepOverrides {
    /// Schemes to compare, comma-separated registry names or scheme strings (commas inside
    /// brackets or parentheses, as in `prk(b = [...], ...)`, belong to the scheme)
    #[arg(long, value_parser = scheme_list)]
    pub schemes: Option<SchemeList>,
    /// Smallest time step of the grid
    #[arg(long, allow_negative_numbers = true)]
    pub dt_min: Option<f64>,
    /// Largest time step of the grid
    #[arg(long, allow_negative_numbers = true)]
    pub dt_max: Option<f64>,
    /// Ratio of neighbouring time steps (default 1.15)
    #[arg(long, allow_negative_numbers = true)]
    pub dt_factor: Option<f64>,
    /// Scheme whose efficiency is 1
    #[arg(long)]
    pub reference: Option<String>,
    /// Whose relative error gives the critical dt: T_C against k_B T (default) or, in a
    /// sheared scene, the shear viscosity against the baseline run
    #[arg(long, value_enum)]
    pub observable: Option<Observable>,
}

impl Scene {
    /// Parse TOML text; `path` names the source in messages.
    pub fn from_toml(text: &str, path: &str) -> Result<Scene, SceneError> {
        toml::from_str(text).map_err(|e| SceneError::Toml {
            path: path.into(),
            message: e.to_string(),
        })
    }

    /// Read a scene file.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|source| SceneError::Io {
            path: path.display().to_string(),
            source,
        })?;
        Scene::from_toml(&text, &path.display().to_string())
    }

    /// The scene file of `o` (or the default scene) with `o`'s flags applied, validated.
    pub fn resolve(o: &Overrides) -> Result<Scene, SceneError> {
        let mut s = match &o.scene {
            Some(path) => Scene::load(path)?,
            None => Scene::default(),
        };
        macro_rules! set {
            ($($key:ident),*) => { $(if let Some(v) = &o.$key { s.$key = v.clone(); })* };
        }
        set!(
            scheme,
            gamma,
            dt,
            time,
            n,
            density,
            a,
            kbt,
            mass,
            weight_exponent,
            seed,
            runs,
            threads
        );
        if let Some(k) = o.shear_rate {
            s.shear_rate = Some(k);
        }
        s.energy_balance |= o.energy_balance;
        s.validate()?;
        Ok(s)
    }

    /// `o`'s keys applied to the scene's `[sweep]` table (or the default one), validated.
    pub fn apply_sweep(&mut self, o: &SweepOverrides) -> Result<(), SceneError> {
        let mut w = self.sweep.clone().unwrap_or_default();
        macro_rules! set {
            ($($key:ident),*) => { $(if let Some(v) = &o.$key { w.$key = v.clone(); })* };
        }
        if let Some(list) = &o.schemes {
            w.schemes = list.0.clone();
        }
        set!(dt_min, dt_max, dt_factor, reference, observable);
        self.sweep = Some(w);
        if let Some(t) = &self.trajectory {
            return Err(ParamError::new(
                "trajectory.file",
                t.file.display(),
                "trajectories are written by `dpd run` only: remove [trajectory] for a sweep",
            )
            .into());
        }
        self.validate()?;
        Ok(())
    }

    /// Check every key; the first invalid one is reported by name.
    pub fn validate(&self) -> Result<(), ParamError> {
        for (key, v) in [
            ("density", self.density),
            ("kbt", self.kbt),
            ("mass", self.mass),
            ("weight_exponent", self.weight_exponent),
            ("dt", self.dt),
            ("time", self.time),
            ("sample_interval", self.sample_interval),
        ] {
            positive(key, v)?;
        }
        for (key, v) in [("a", self.a), ("gamma", self.gamma)] {
            require(key, v, v.is_finite() && v >= 0.0, "must be finite and >= 0")?;
        }
        let f = self.average_fraction;
        require(
            "average_fraction",
            f,
            f > 0.0 && f <= 1.0,
            "must be in (0, 1]",
        )?;
        require("runs", self.runs, self.runs >= 1, "must be at least 1")?;
        check_steps(self.time, "dt", self.dt)?;
        let max_threads = MAX_THREADS_PER_CORE * cores();
        require(
            "threads",
            self.threads,
            self.threads <= max_threads,
            &format!(
                "must be at most {max_threads} ({MAX_THREADS_PER_CORE} per core of this \
                 machine; 0 means one per core)"
            ),
        )?;
        require(
            "skin",
            self.skin,
            self.skin.is_finite() && (0.0..=1.0).contains(&self.skin),
            "must be in [0, 1] (in units of r_c)",
        )?;
        let min_edge = 2.0 * (1.0 + self.skin);
        let max_density = MAX_PARTICLES as f64 / min_edge.powi(3);
        require(
            "density",
            self.density,
            self.density <= max_density,
            &format!(
                "must be at most {} (the smallest box, of edge {min_edge}, then holds \
                 {MAX_PARTICLES} particles)",
                max_density.floor()
            ),
        )?;
        require(
            "n",
            self.n,
            self.n <= MAX_PARTICLES,
            &format!("must be at most {MAX_PARTICLES}"),
        )?;
        let edge = self.lengths()?.into_iter().fold(f64::INFINITY, f64::min);
        if self.box_lengths.is_some() {
            require(
                "box",
                format!("{:?}", self.box_lengths),
                edge >= min_edge && self.particles() >= 2 && self.particles() <= MAX_PARTICLES,
                &format!(
                    "every edge must be >= {min_edge} and the box hold 2 to {MAX_PARTICLES} \
                     particles at density {}",
                    self.density
                ),
            )?;
        } else {
            require(
                "n",
                self.n,
                self.n >= 2 && edge >= min_edge,
                &format!(
                    "must be at least 2 and fill a cube of edge >= {min_edge} at density {} \
                     (n >= {:.0})",
                    self.density,
                    (min_edge.powi(3) * self.density).ceil()
                ),
            )?;
        }
        if let Some(k) = self.shear_rate {
            require("shear_rate", k, k.is_finite(), "must be finite")?;
        }
        if let Some(g) = self.body_force {
            require("body_force", g, g.is_finite(), "must be finite")?;
        }
        if let Some(w) = &self.walls {
            w.walls()?;
        }
        if let Some(p) = &self.profile {
            require("profile.bins", p.bins, p.bins >= 1, "must be at least 1")?;
            require(
                "profile.axis",
                p.axis,
                p.axis <= 2,
                "must be 0 (x), 1 (y) or 2 (z)",
            )?;
        }
        if let Some(t) = &self.trajectory {
            t.validate()?;
        }
        if let Some(init) = &self.init {
            InitSpec::parse(init)?;
        }
        if let Some(r) = &self.rdf {
            let half = 0.5 * edge;
            require(
                "rdf.r_max",
                r.r_max,
                r.r_max > 0.0 && r.r_max <= half,
                &format!("must be in (0, {half:.4}] (half the box edge)"),
            )?;
            require("rdf.bins", r.bins, r.bins >= 1, "must be at least 1")?;
            if let Some(interval) = r.interval {
                positive("rdf.interval", interval)?;
            }
        }
        if let Some(v) = &self.vacf {
            positive("vacf.max_lag", v.max_lag)?;
            require(
                "vacf.origin_every",
                v.origin_every,
                v.origin_every >= 1,
                "must be at least 1",
            )?;
        }
        if let Some(w) = &self.sweep {
            w.validate()?;
            check_steps(self.time, "sweep.dt_min", w.dt_min)?;
            check_steps(self.time, "sweep.dt_max", w.dt_max)?;
            check_steps(self.time, "sweep.baseline_dt", w.baseline_dt())?;
            require(
                "sweep.observable",
                w.observable.name(),
                w.observable != Observable::Viscosity || self.shear_rate.is_some_and(|k| k != 0.0),
                "needs a non-zero shear_rate (`shear_rate` in the scene or --shear-rate); \
                 valid without it: configurational-temperature",
            )?;
            require(
                "sweep.observable",
                w.observable.name(),
                self.walls.is_none(),
                "is not measured between walls (T_C is null there and viscosity needs \
                 shear, which walls exclude): sweep a scene without [walls]",
            )?;
        }
        Ok(())
    }

    /// Steps of a run at `dt`: round(time / dt), which [`Scene::validate`] keeps between 1
    /// and [`MAX_STEPS`] (at least 1 here too).
    pub fn steps(&self, dt: f64) -> u64 {
        ((self.time / dt).round() as u64).max(1)
    }

    /// Steps between samples at `dt` (at least 1).
    pub fn sample_every(&self, dt: f64) -> u64 {
        ((self.sample_interval / dt).round() as u64).max(1)
    }

    /// Samples between g(r) records at `dt` (at least 1); see [`RdfSpec::interval`].
    pub fn rdf_stride(&self, dt: f64) -> u64 {
        let sample = self.sample_every(dt) as f64 * dt;
        match self.rdf.as_ref().and_then(|r| r.interval) {
            Some(interval) => ((interval / sample).round() as u64).max(1),
            None => 1,
        }
    }

    /// The pair-force parameters.
    pub fn params(&self) -> Result<Params, ParamError> {
        Params::builder()
            .a(self.a)
            .gamma(self.gamma)
            .kbt(self.kbt)
            .weight_exponent(self.weight_exponent)
            .build()
    }

    /// The box: `box` if given, else the cube of `n` particles at `density`.
    pub fn periodic_box(&self) -> Result<PeriodicBox, ParamError> {
        match self.box_lengths {
            Some(l) => PeriodicBox::new(l),
            None => cubic_box(self.n, self.density),
        }
    }

    fn lengths(&self) -> Result<[f64; 3], ParamError> {
        Ok(self.periodic_box()?.lengths().into())
    }

    /// Number of particles (wall particles included).
    pub fn particles(&self) -> usize {
        match self.periodic_box() {
            Ok(bx) if self.box_lengths.is_some() => (self.density * bx.volume()).round() as usize,
            _ => self.n,
        }
    }

    /// The initial state of run `seed` at time step `dt`: uniform positions, Maxwell momenta
    /// with the total momentum removed (with `init`, the frame's positions, velocities, masses
    /// and types instead); with `[walls]`, the particles outside the channel are frozen (and
    /// their momenta zeroed).
    pub fn system(&self, dt: f64, seed: u64) -> Result<System, ParamError> {
        let bx = self.periodic_box()?;
        let n = self.particles();
        let params = self.params()?;
        let (q, mut p, masses, kinds) = match &self.init {
            Some(init) => {
                let frame = InitSpec::parse(init)?.read(n, bx.lengths().into())?;
                initial_state(&frame, self.mass, params.types())?
            }
            None => {
                let masses = vec![self.mass; n];
                let q = uniform_positions(&bx, n, seed);
                let p = maxwell_momenta(&masses, self.kbt, seed);
                (q, p, masses, vec![0; n])
            }
        };
        let mut builder = System::builder(params, bx, q.clone())
            .masses(masses)
            .kinds(kinds)
            .dt(dt)
            .seed(seed)
            .skin(self.skin);
        if let Some(w) = &self.walls {
            let walls = w.walls()?;
            let frozen = freeze_outside(&walls, &q, &mut p);
            builder = builder.walls(walls).frozen(frozen);
        }
        if let Some(k) = self.shear_rate {
            builder = builder.shear_rate(k);
        }
        if let Some(g) = self.body_force {
            builder = builder.body_force(Vec3::new(g, 0.0, 0.0));
        }
        builder.momenta(p).build()
    }

    /// The effective parameters as TOML, for headers; with `box`, the ignored `n` is left out
    /// and the particle count given in a comment.
    pub fn to_toml(&self) -> String {
        let mut table = match toml::Table::try_from(self) {
            Ok(table) => table,
            Err(e) => return format!("(scene not printable: {e})"),
        };
        let mut out = String::new();
        if self.box_lengths.is_some() {
            table.remove("n");
            out = format!("# {} particles (density x box volume)\n", self.particles());
        }
        out + &table.to_string()
    }
}

impl SweepSpec {
    fn validate(&self) -> Result<(), ParamError> {
        require(
            "sweep.schemes",
            format!("{:?}", self.schemes),
            !self.schemes.is_empty(),
            "must name at least one scheme",
        )?;
        positive("sweep.dt_min", self.dt_min)?;
        require(
            "sweep.dt_max",
            self.dt_max,
            self.dt_max.is_finite() && self.dt_max >= self.dt_min,
            &format!("must be finite and >= sweep.dt_min = {}", self.dt_min),
        )?;
        let f = self.dt_factor;
        require(
            "sweep.dt_factor",
            f,
            f.is_finite() && f > 1.0,
            "must be finite and > 1",
        )?;
        let points = (self.dt_max / self.dt_min).ln() / f.ln();
        require(
            "sweep.dt_factor",
            f,
            points < 1000.0,
            "gives more than 1000 grid points",
        )?;
        require(
            "sweep.reference",
            &self.reference,
            self.schemes.contains(&self.reference),
            &format!("must be one of sweep.schemes {:?}", self.schemes),
        )?;
        if let Some(dt) = self.baseline_dt {
            positive("sweep.baseline_dt", dt)?;
        }
        Ok(())
    }

    /// The time steps dt_min dt_factor^k up to dt_max (within a relative 1e-9).
    pub fn grid(&self) -> Vec<f64> {
        (0..)
            .map(|k| self.dt_min * self.dt_factor.powi(k))
            .take_while(|&dt| dt <= self.dt_max * (1.0 + 1e-9))
            .collect()
    }

    /// Time step of the baseline run.
    pub fn baseline_dt(&self) -> f64 {
        self.baseline_dt.unwrap_or(self.dt_min)
    }
}

/// The schemes of `--schemes`, split at the commas outside brackets and parentheses.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SchemeList(pub Vec<String>);

/// Splits `text` at top-level commas: `"vv, prk(b = [1/2, 1/2], bh = [1, 0])"` is two schemes.
pub fn scheme_list(text: &str) -> Result<SchemeList, String> {
    let mut schemes = Vec::new();
    let (mut depth, mut start) = (0i64, 0);
    for (i, c) in text.char_indices() {
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            ',' if depth == 0 => {
                schemes.push(text[start..i].trim().to_string());
                start = i + 1;
            }
            _ => {}
        }
    }
    schemes.push(text[start..].trim().to_string());
    if schemes.iter().any(String::is_empty) {
        return Err("empty scheme in the list (two commas in a row?)".into());
    }
    Ok(SchemeList(schemes))
}

/// Most steps of one run: a longer run is refused rather than left to run for days.
pub const MAX_STEPS: u64 = 1_000_000_000;
/// Most worker threads per core.
pub const MAX_THREADS_PER_CORE: usize = 8;
/// Most particles of a scene.
pub const MAX_PARTICLES: usize = 100_000_000;

/// Cores of this machine (1 if unknown).
fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// Checks that a run of `time` at step `key` = `dt` (already checked positive) has between 1
/// and [`MAX_STEPS`] steps.
fn check_steps(time: f64, key: &str, dt: f64) -> Result<(), ParamError> {
    let steps = (time / dt).round();
    require(
        key,
        dt,
        steps >= 1.0,
        &format!(
            "gives round(time / {key}) = 0 steps with time = {time}: must be at most twice \
             time, {}",
            2.0 * time
        ),
    )?;
    require(
        key,
        dt,
        steps <= MAX_STEPS as f64,
        &format!(
            "gives {steps:e} steps with time = {time}, more than the {MAX_STEPS:e} steps a run \
             may take: raise {key} or shorten time"
        ),
    )
}

fn require(key: &str, value: impl ToString, ok: bool, allowed: &str) -> Result<(), ParamError> {
    if ok {
        Ok(())
    } else {
        Err(ParamError::new(key, value, allowed))
    }
}

fn positive(key: &str, v: f64) -> Result<(), ParamError> {
    require(key, v, v.is_finite() && v > 0.0, "must be finite and > 0")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn error_of(text: &str) -> String {
        match Scene::from_toml(text, "t.toml").and_then(|s| Ok(s.validate()?)) {
            Ok(()) => panic!("{text:?} was accepted"),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn a_scene_names_only_what_it_needs() {
        let s = Scene::from_toml("gamma = 40.5\n[rdf]\nbins = 20\n", "t").unwrap();
        assert_eq!((s.gamma, s.n, s.rdf.unwrap().bins), (40.5, 500, 20));
        assert!(s.vacf.is_none() && s.sweep.is_none());
    }

    #[test]
    fn g_of_r_is_sampled_every_interval_in_whole_samples() {
        let s = Scene::from_toml("[rdf]\ninterval = 0.5\n", "t").unwrap();
        // Samples every 0.1 / 0.05 = 2 steps; 0.5 / 0.1 = 5 samples per g(r) record.
        assert_eq!((s.sample_every(0.05), s.rdf_stride(0.05)), (2, 5));
        // At dt = 0.3 every step is a sample (0.3 time units apart): 0.5 / 0.3 rounds to 2.
        assert_eq!((s.sample_every(0.3), s.rdf_stride(0.3)), (1, 2));
        // An interval shorter than the sampling records every sample.
        assert_eq!(s.rdf_stride(2.0), 1);
        assert_eq!(
            Scene::from_toml("[rdf]\n", "t").unwrap().rdf_stride(0.05),
            1
        );
    }

    #[test]
    fn unknown_keys_and_invalid_values_name_the_key() {
        for (text, key) in [
            ("gama = 4.5", "gama"),
            ("[sweep]\ndt_mni = 0.1", "dt_mni"),
            ("gamma = -1.0", "gamma"),
            ("gamma = \"x\"", "gamma"),
            ("kbt = 0.0", "kbt"),
            ("n = 10", "n"),
            ("skin = -0.1", "skin"),
            ("skin = 1.5", "skin"),
            // Edge 2.37: enough for the default skin 0 (2 r_c), not for 0.5 (2 (r_c + skin)).
            ("n = 40\nskin = 0.5", "n"),
            ("average_fraction = 1.5", "average_fraction"),
            ("runs = 0", "runs"),
            ("[rdf]\nr_max = 9.0", "rdf.r_max"),
            ("[rdf]\ninterval = 0.0", "rdf.interval"),
            ("[sweep]\ndt_factor = 1.0", "sweep.dt_factor"),
            ("[sweep]\ndt_min = 0.1\ndt_max = 0.01", "sweep.dt_max"),
            ("[sweep]\nreference = \"abo\"", "sweep.reference"),
        ] {
            let e = error_of(text);
            assert!(e.contains(key), "{text:?}: {e}");
        }
    }

    #[test]
    fn the_default_skin_allows_a_box_of_edge_two_r_c() {
        let scene = Scene::from_toml("n = 40", "t.toml").unwrap();
        assert_eq!(scene.skin, 0.0);
        scene.validate().unwrap();
    }

    #[test]
    fn overrides_replace_scene_keys() {
        let o = Overrides {
            gamma: Some(450.0),
            n: Some(100),
            ..Default::default()
        };
        let s = Scene::resolve(&o).unwrap();
        assert_eq!((s.gamma, s.n, s.density), (450.0, 100, 3.0));
        let bad = Overrides {
            dt: Some(f64::NAN),
            ..Default::default()
        };
        assert!(Scene::resolve(&bad).unwrap_err().to_string().contains("dt"));
    }

    #[test]
    fn sweep_overrides_replace_sweep_keys_and_are_validated() {
        let mut s = Scene::from_toml("[sweep]\ndt_max = 0.1\n", "t").unwrap();
        let o = SweepOverrides {
            schemes: Some(SchemeList(vec!["aboba".into(), "vv".into()])),
            dt_min: Some(0.05),
            ..Default::default()
        };
        s.apply_sweep(&o).unwrap();
        let w = s.sweep.clone().unwrap();
        assert_eq!((w.schemes.len(), w.dt_min, w.dt_max), (2, 0.05, 0.1));
        let bad = SweepOverrides {
            reference: Some("baoab".into()),
            ..Default::default()
        };
        let e = s.apply_sweep(&bad).unwrap_err().to_string();
        assert!(
            e.starts_with("scene: invalid sweep.reference = baoab"),
            "{e}"
        );
    }

    #[test]
    fn scheme_lists_split_at_top_level_commas_only() {
        let list = scheme_list(
            "vv, prk(b = [7/24, 3/4, -1/24], bh = [2/3, -2/3, 1], kick = B) O,A(1/2) B A(1/2)",
        )
        .unwrap();
        assert_eq!(
            list.0,
            vec![
                "vv",
                "prk(b = [7/24, 3/4, -1/24], bh = [2/3, -2/3, 1], kick = B) O",
                "A(1/2) B A(1/2)"
            ]
        );
        assert!(scheme_list("vv,,aboba").is_err());
    }

    #[test]
    fn grid_is_geometric_and_inclusive() {
        let w = SweepSpec {
            dt_min: 0.01,
            dt_max: 0.04,
            dt_factor: 2.0,
            ..Default::default()
        };
        assert_eq!(w.grid(), vec![0.01, 0.02, 0.04]);
    }

    #[test]
    fn every_shipped_scene_is_valid() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
        let mut count = 0;
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                // scenes/papers/: paper items, checked by the paper module's tests.
                continue;
            }
            Scene::load(&path).unwrap().validate().unwrap();
            count += 1;
        }
        assert!(count >= 6);
    }
}
