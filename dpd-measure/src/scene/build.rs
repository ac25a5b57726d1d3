//! The system of a scene: its sections put together into a `dpd_core::System`.

use super::Scene;
use crate::start::{initial_state, InitSpec};
use dpd_core::init::{freeze_outside, maxwell_momenta, uniform_positions};
use dpd_core::{ParamError, System, Vec3};

impl Scene {
    /// The initial state of run `seed` at time step `dt`: uniform positions, Maxwell momenta
    /// with the total momentum removed (with `init`, the frame's positions, velocities, masses
    /// and types instead); with `[walls]`, the particles outside the channel are frozen (and
    /// their momenta zeroed).
    pub fn system(&self, dt: f64, seed: u64) -> Result<System, ParamError> {
        let (geometry, physics) = (&self.geometry, &self.physics);
        let bx = geometry.periodic_box()?;
        let n = geometry.particles();
        let params = physics.params()?;
        let (q, mut p, masses, kinds) = match &geometry.init {
            Some(init) => {
                let frame = InitSpec::parse(init)?.read(n, bx.lengths().into())?;
                initial_state(&frame, physics.mass, params.types())?
            }
            None => {
                let masses = vec![physics.mass; n];
                let q = uniform_positions(&bx, n, seed);
                let p = maxwell_momenta(&masses, physics.kbt, seed);
                (q, p, masses, vec![0; n])
            }
        };
        let mut builder = System::builder(params, bx, q.clone())
            .masses(masses)
            .kinds(kinds)
            .dt(dt)
            .seed(seed)
            .skin(geometry.skin);
        if let Some(w) = &geometry.walls {
            let walls = w.walls()?;
            let frozen = freeze_outside(&walls, &q, &mut p);
            builder = builder.walls(walls).frozen(frozen);
        }
        if let Some(k) = physics.shear_rate {
            builder = builder.shear_rate(k);
        }
        if let Some(g) = physics.body_force {
            builder = builder.body_force(Vec3::new(g, 0.0, 0.0));
        }
        builder.momenta(p).build()
    }
}
