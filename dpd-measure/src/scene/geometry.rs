//! The geometry section: the box, how many particles it holds, the walls across it, the state
//! the runs start from and the neighbour list's skin.

use super::check::{positive, require, MAX_PARTICLES};
use crate::start::InitSpec;
use dpd_core::init::cubic_box;
use dpd_core::system::DEFAULT_SKIN;
use dpd_core::{ParamError, PeriodicBox, Walls};
use serde::{Deserialize, Serialize};

/// Keys `n`, `density`, `box`, `skin`, `init`, `init_reset` and the table `[walls]`. Lengths
/// in units of r_c = 1.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Geometry {
    /// Number of particles in the cubic periodic box.
    pub n: usize,
    /// Number density.
    pub density: f64,
    /// Verlet-list skin in units of r_c: pairs within r_c + skin are listed, and the list is
    /// rebuilt once a particle may have crossed it. 0 (the default) rebuilds the cell lists
    /// every step. It changes the cost and the order of the pair sweeps, not the physics.
    pub skin: f64,
    /// Box edges `[L_x, L_y, L_z]`; then `n` is ignored and the box holds
    /// `round(density V)` particles (wall slabs included). Default: the cube of `n` particles.
    #[serde(rename = "box")]
    pub box_lengths: Option<[f64; 3]>,
    pub walls: Option<WallSpec>,
    /// Start from a frame of a GSD file, `"FILE.gsd"` (its last frame) or `"FILE.gsd:K"`, or
    /// from a LAMMPS data file, `"FILE.data"`; its box and particle count are the scene's
    /// unless it sets `n`, `box` or `density`. The trajectory's step, time and images go on
    /// from the frame's, as HOOMD's do.
    pub init: Option<String>,
    /// With `init`: count the trajectory's step, time and images from 0 instead.
    pub init_reset: bool,
}

/// Which of the keys `n`, `box` and `density` a scene sets (the others take their defaults).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Given {
    pub n: bool,
    pub box_lengths: bool,
    pub density: bool,
}

/// Walls across z: the channel `lower <= z <= upper` holds the fluid, the slabs outside it
/// are filled with frozen particles at the fluid density, moving along x at `velocity`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct WallSpec {
    pub lower: f64,
    pub upper: f64,
    /// x-velocities of the lower and upper wall.
    pub velocity: [f64; 2],
}

impl Default for Geometry {
    /// The standard box of algorithms.md section 8: 500 particles at density 3.
    fn default() -> Self {
        Geometry {
            n: 500,
            density: 3.0,
            skin: DEFAULT_SKIN,
            box_lengths: None,
            walls: None,
            init: None,
            init_reset: false,
        }
    }
}

impl Default for WallSpec {
    fn default() -> Self {
        WallSpec {
            lower: 1.0,
            upper: 9.0,
            velocity: [0.0, 0.0],
        }
    }
}

impl WallSpec {
    pub fn walls(&self) -> Result<Walls, ParamError> {
        Walls::new(self.lower, self.upper, self.velocity)
    }
}

impl Geometry {
    pub fn validate(&self) -> Result<(), ParamError> {
        positive("density", self.density)?;
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
        let edge = self.shortest_edge()?;
        if self.box_lengths.is_some() {
            let n = self.particles();
            require(
                "box",
                format!("{:?}", self.box_lengths),
                edge >= min_edge && (2..=MAX_PARTICLES).contains(&n),
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
        if let Some(w) = &self.walls {
            w.walls()?;
        }
        require(
            "init_reset",
            self.init_reset,
            !self.init_reset || self.init.is_some(),
            "resets the counters of a run started from `init`: set init too, or leave it out",
        )?;
        if let Some(init) = &self.init {
            InitSpec::parse(init)?;
        }
        Ok(())
    }

    /// With `init`, the size the scene leaves to the file: `given` says which of `n`, `box`
    /// and `density` the scene sets; without `box` the box is the file's, and without
    /// `density` the density is that of the file's particles (or of `n`) in the box. What the
    /// scene sets is kept, and a count or box other than the file's is refused when the run
    /// starts, naming both.
    pub fn size_from_init(&mut self, given: Given) -> Result<(), ParamError> {
        let Some(init) = &self.init else {
            return Ok(());
        };
        if given.box_lengths && given.density {
            return Ok(());
        }
        let (particles, lengths) = InitSpec::parse(init)?.size()?;
        let lengths = self
            .box_lengths
            .filter(|_| given.box_lengths)
            .unwrap_or(lengths);
        if !given.density {
            let count = if given.n { self.n } else { particles };
            self.density = count as f64 / lengths.iter().product::<f64>();
        }
        self.box_lengths = Some(lengths);
        Ok(())
    }

    /// The box: `box` if given, else the cube of `n` particles at `density`.
    pub fn periodic_box(&self) -> Result<PeriodicBox, ParamError> {
        match self.box_lengths {
            Some(l) => PeriodicBox::new(l),
            None => cubic_box(self.n, self.density),
        }
    }

    /// The shortest edge of the box.
    pub fn shortest_edge(&self) -> Result<f64, ParamError> {
        let lengths: [f64; 3] = self.periodic_box()?.lengths().into();
        Ok(lengths.into_iter().fold(f64::INFINITY, f64::min))
    }

    /// Number of particles (wall particles included).
    pub fn particles(&self) -> usize {
        match self.periodic_box() {
            Ok(bx) if self.box_lengths.is_some() => (self.density * bx.volume()).round() as usize,
            _ => self.n,
        }
    }
}
