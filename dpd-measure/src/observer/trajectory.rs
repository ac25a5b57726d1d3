//! Trajectories of `dpd run` (the scene's `[trajectory]` table or `--trajectory FILE --every
//! T`): the initial state and a frame every `every` time units, written by the
//! `dpd-trajectory` crate.

use super::interface::{Boxed, End, Observer, Setup};
use crate::images::Images;
use crate::result::RunResult;
use crate::scene::{Field, TrajectorySpec};
use crate::start::Origin;
use dpd_core::observe::thermo;
use dpd_core::{ParamError, System, Topology, Vec3};
use dpd_trajectory::{Bonds, Frame, Writer};
use std::path::PathBuf;

/// The observables a frame logs, in the order of [`frame`]'s values.
const LOG_NAMES: [&str; 4] = [
    "kinetic_temperature",
    "configurational_temperature",
    "potential_energy",
    "pressure",
];

/// Writes one run's frames: the state at step 0 and every `every_steps` after. As an
/// [`Observer`] it is called at every step of [`Observer::next_stop`]; the Python module drives
/// it so too.
pub struct Recorder {
    writer: Writer,
    fields: Vec<Field>,
    every_steps: u64,
    origin: Origin,
    path: PathBuf,
    /// With the `image` field: the images, which need the positions after every step.
    images: Option<Images>,
    names: TypeNames,
}

/// The names a trajectory gives the particle types (GSD `particles/types`) and the bond types
/// (`bonds/types`), each in type order ([`crate::Scene::trajectory_names`]).
#[derive(Clone, Debug, PartialEq)]
pub struct TypeNames {
    pub particles: Vec<String>,
    pub bonds: Vec<String>,
}

/// The recorder of `[trajectory]`: creates the file of the run and writes the initial state as
/// frame 0.
pub(super) fn new<'a>(
    setup: &Setup<'a>,
    sys: &mut System,
) -> Result<Option<Boxed<'a>>, ParamError> {
    let Some(spec) = &setup.scene.output.trajectory else {
        return Ok(None);
    };
    let runs = setup.scene.run.runs;
    let names = setup.scene.trajectory_names(sys);
    let origin = setup.scene.origin(setup.dt)?;
    let recorder = Recorder::start(spec, setup.dt, (setup.seed, runs), names, origin, sys)?;
    Ok(Some(Box::new(recorder)))
}

impl Recorder {
    /// Create the file of run `seed` and write the initial state as frame 0. `(seed, runs)`
    /// name the file; `names` name the types. Steps, times and images go on from `origin`
    /// (the default origin: 0, 0 and no image).
    pub fn start(
        spec: &TrajectorySpec,
        dt: f64,
        (seed, runs): (u64, u64),
        names: TypeNames,
        origin: Origin,
        sys: &mut System,
    ) -> Result<Recorder, ParamError> {
        let fields = match &spec.fields {
            Some(fields) => fields.clone(),
            None => {
                let mut all = vec![Field::Velocity, Field::Mass, Field::Observables];
                if sys.shear().is_none() {
                    all.push(Field::Image);
                }
                all
            }
        };
        let images = match fields.contains(&Field::Image) {
            true => Some(Images::start(sys, origin.images.as_deref())?),
            false => None,
        };
        let path = spec.path(seed, runs);
        let logged: &[&str] = match fields.contains(&Field::Observables) {
            true => &LOG_NAMES,
            false => &[],
        };
        let writer = Writer::create(&path, logged)
            .map_err(|e| ParamError::new("trajectory.file", path.display(), e.to_string()))?;
        let mut r = Recorder {
            writer,
            fields,
            every_steps: spec.every_steps(dt),
            origin,
            path,
            images,
            names,
        };
        r.record(sys)?;
        Ok(r)
    }

    fn record(&mut self, sys: &mut System) -> Result<(), ParamError> {
        let mut f = frame(sys, &self.fields, &self.names);
        f.step += self.origin.step;
        f.time += self.origin.time;
        f.images = self.images.as_ref().map(|i| i.by_id().to_vec());
        self.writer
            .append(&f)
            .map_err(|e| ParamError::new("trajectory.file", self.path.display(), e.to_string()))
    }
}

impl Observer for Recorder {
    /// The next frame, or the next step when it follows images.
    fn next_stop(&self, step: u64) -> u64 {
        match self.images {
            Some(_) => step + 1,
            None => (step / self.every_steps + 1) * self.every_steps,
        }
    }

    /// Follow the images over the steps since the last stop (one step: see `next_stop`) and
    /// append a frame if one is due at the system's step.
    fn after_steps(&mut self, sys: &mut System) -> Result<(), ParamError> {
        if let Some(images) = &mut self.images {
            images.update(sys);
        }
        if sys.step().is_multiple_of(self.every_steps) {
            self.record(sys)?;
        }
        Ok(())
    }

    fn finish(self: Box<Self>, _: &mut System, _: &End, _: &mut RunResult) {}
}

/// The system's state as a frame with type names `names`, particles in the order of their
/// ids (the order in which the system was built; the storage order changes as the system
/// sorts itself), at its own step and time (step x dt), with the system's bonds.
fn frame(sys: &mut System, fields: &[Field], names: &TypeNames) -> Frame {
    let ids: Vec<usize> = sys.ids().iter().map(|&i| i as usize).collect();
    let in_id_order = |values: &[Vec3], scale: &dyn Fn(usize) -> f64| {
        let mut out = vec![[0.0; 3]; values.len()];
        for (k, &i) in ids.iter().enumerate() {
            let s = scale(k);
            out[i] = [values[k].x * s, values[k].y * s, values[k].z * s];
        }
        out
    };
    let masses = sys.masses().to_vec();
    let positions = in_id_order(sys.positions(), &|_| 1.0);
    let velocities = fields
        .contains(&Field::Velocity)
        .then(|| in_id_order(sys.momenta(), &|k| 1.0 / masses[k]));
    let mut typeid = vec![0; ids.len()];
    let mut mass = vec![0.0; ids.len()];
    for (k, &i) in ids.iter().enumerate() {
        typeid[i] = u32::from(sys.kinds()[k]);
        mass[i] = masses[k];
    }
    let log = match fields.contains(&Field::Observables) {
        true => {
            let t = thermo(sys);
            let values = [
                t.kinetic_temperature,
                configurational_temperature(t.config_numerator, t.config_denominator),
                t.potential_energy,
                t.pressure,
            ];
            LOG_NAMES
                .iter()
                .map(|n| n.to_string())
                .zip(values)
                .collect()
        }
        false => Vec::new(),
    };
    Frame {
        step: sys.step(),
        time: sys.step() as f64 * sys.dt(),
        dt: sys.dt(),
        box_lengths: sys.boundary().lengths().into(),
        positions,
        velocities,
        images: None,
        typeid,
        types: names.particles.clone(),
        masses: fields.contains(&Field::Mass).then_some(mass),
        log,
        bonds: sys
            .topology()
            .filter(|t| !t.bonds().is_empty())
            .map(|t| bonds(t, &names.bonds)),
    }
}

/// The bonds of `topology` as a frame holds them (GSD `bonds/...`, which OVITO draws), by
/// particle id, the bond types named `types`.
fn bonds(topology: &Topology, types: &[String]) -> Bonds {
    let b = topology.bonds();
    Bonds {
        types: types.to_vec(),
        typeid: b.iter().map(|b| u32::from(b.kind)).collect(),
        group: b.iter().map(|b| [b.i, b.j]).collect(),
    }
}

/// `k_B T_C` of one state, `sum |F^C|^2 / sum lap U`, or NaN (undefined) where the Laplacian
/// sum is not positive. The soft potential's Laplacian, `a (3 r - 2) / r` for r_c = 1, is
/// negative for pairs closer than 2/3: a random start, full of such pairs, can have a sum near
/// zero or below it, and the quotient is then no temperature (-437378 was once logged).
fn configurational_temperature(numerator: f64, denominator: f64) -> f64 {
    if denominator > 0.0 {
        numerator / denominator
    } else {
        f64::NAN
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    /// A uniform random start of the standard box has more pairs closer than 2/3 than the
    /// fluid: its Laplacian sum is negative here (seed 3, N = 300), and frame 0 logged
    /// T_C = -28.2. It is undefined there, and a number again once the fluid has relaxed.
    #[test]
    fn t_c_is_undefined_where_the_laplacian_sum_is_not_positive() {
        assert!(configurational_temperature(5.0, -0.1).is_nan());
        assert!(configurational_temperature(5.0, 0.0).is_nan());
        assert_eq!(configurational_temperature(5.0, 2.0), 2.5);
        let mut scene = Scene::default();
        scene.geometry.n = 300;
        let mut sys = scene.system(0.05, 3).unwrap();
        let names = scene.trajectory_names(&sys);
        let logged = |sys: &mut System| frame(sys, &[Field::Observables], &names).log[1].1;
        assert!(thermo(&mut sys).config_denominator <= 0.0);
        assert!(logged(&mut sys).is_nan());
        let aboba = dpd_schemes::registry::resolve("aboba").unwrap();
        sys.advance(aboba.as_ref(), 40).unwrap();
        let t_c = logged(&mut sys);
        assert!(t_c > 0.5 && t_c < 2.0, "{t_c}");
    }
}
