//! The number density of each species in slabs across an axis, over the window (`[profile]`
//! in a scene with `[[species]]`): the profile of a demixed mixture's slabs.

use super::interface::{Boxed, End, Observer, Setup};
use crate::result::RunResult;
use dpd_core::{ParamError, System};
use std::collections::BTreeMap;

/// Slab densities of each type; also used by the Python module's `measure`.
pub struct SpeciesProfile {
    axis: usize,
    length: f64,
    slab_volume: f64,
    /// `counts[t * bins + k]`: particles of type t in slab k, summed over the samples.
    counts: Vec<u64>,
    bins: usize,
    names: Vec<String>,
    samples: u64,
}

pub(super) fn new<'a>(
    setup: &Setup<'a>,
    sys: &mut System,
) -> Result<Option<Boxed<'a>>, ParamError> {
    let (Some(spec), Some(_)) = (&setup.scene.observe.profile, &setup.scene.species.species) else {
        return Ok(None);
    };
    let types = sys.params().types();
    Ok(Some(Box::new(SpeciesProfile::new(
        sys,
        spec.axis,
        spec.bins,
        setup.scene.type_names(types),
    ))))
}

impl SpeciesProfile {
    /// `bins` equal slabs across `axis` (checked by the scene) of `sys`'s box.
    pub fn new(sys: &System, axis: usize, bins: usize, names: Vec<String>) -> SpeciesProfile {
        let bx = sys.boundary();
        SpeciesProfile {
            axis,
            length: bx.lengths()[axis],
            slab_volume: bx.volume() / bins as f64,
            counts: vec![0; names.len() * bins],
            bins,
            names,
            samples: 0,
        }
    }

    /// Add the mobile particles (frozen wall particles are left out) of the current state.
    pub fn record(&mut self, sys: &System) {
        let scale = self.bins as f64 / self.length;
        let frozen = sys.frozen();
        for (k, (q, &t)) in sys.positions().iter().zip(sys.kinds()).enumerate() {
            if frozen.is_some_and(|f| f[k]) {
                continue;
            }
            let slab = ((q[self.axis] * scale) as usize).min(self.bins - 1);
            self.counts[usize::from(t) * self.bins + slab] += 1;
        }
        self.samples += 1;
    }

    /// Per species, keyed by name: `[slab centre, number density]` per slab.
    pub fn rows(&self) -> BTreeMap<String, Vec<[f64; 2]>> {
        let width = self.length / self.bins as f64;
        let per = self.samples.max(1) as f64 * self.slab_volume;
        let slabs = self.counts.chunks(self.bins);
        let rows = slabs.map(|c| {
            let each = c.iter().enumerate();
            each.map(|(k, &n)| [(k as f64 + 0.5) * width, n as f64 / per])
                .collect()
        });
        self.names.iter().cloned().zip(rows).collect()
    }
}

impl Observer for SpeciesProfile {
    fn sample(&mut self, sys: &mut System, _: u64) -> Result<(), ParamError> {
        self.record(sys);
        Ok(())
    }

    fn finish(self: Box<Self>, _: &mut System, end: &End, result: &mut RunResult) {
        result.species_profile = (end.stable && self.samples > 0).then(|| self.rows());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use dpd_core::observe::Profile;
    use dpd_core::{Params, PeriodicBox, Vec3};

    /// Particles placed in known slabs are counted there by species, and the species'
    /// densities add up to the density of dpd-core's own slab profile.
    #[test]
    fn slabs_hold_each_species_put_in_them() {
        let bx = PeriodicBox::new([4.0, 4.0, 4.0]).unwrap();
        let q = vec![
            Vec3::new(1.0, 0.5, 1.0),
            Vec3::new(2.0, 0.7, 1.0),
            Vec3::new(1.0, 3.5, 1.0),
            Vec3::new(3.0, 2.5, 1.0),
        ];
        let params = Params::builder()
            .a_matrix(vec![vec![25.0, 40.0], vec![40.0, 25.0]])
            .build()
            .unwrap();
        let sys = dpd_core::System::builder(params, bx, q)
            .kinds(vec![0, 1, 1, 0])
            .build()
            .unwrap();
        let names = vec!["A".to_string(), "B".to_string()];
        let mut profile = SpeciesProfile::new(&sys, 1, 2, names);
        profile.record(&sys);
        profile.record(&sys);
        let rows = profile.rows();
        // Slab y in [0, 2) holds one A and one B, [2, 4) one A and one B; volume 32.
        assert_eq!(rows["A"], [[1.0, 1.0 / 32.0], [3.0, 1.0 / 32.0]]);
        assert_eq!(rows["B"], [[1.0, 1.0 / 32.0], [3.0, 1.0 / 32.0]]);
        let mut along_x = SpeciesProfile::new(&sys, 0, 4, vec!["A".into(), "B".into()]);
        along_x.record(&sys);
        let rows = along_x.rows();
        let mut total = Profile::new(&sys, 0, 4).unwrap();
        total.record(&sys);
        for (k, row) in total.rows().iter().enumerate() {
            assert_eq!(rows["A"][k][1] + rows["B"][k][1], row.density);
        }
        // x = 1 holds the first A and the B at y = 3.5; x = 3 the second A.
        assert_eq!(rows["A"][1][1], 1.0 / 16.0);
        assert_eq!(rows["B"][1][1], 1.0 / 16.0);
        assert_eq!(rows["A"][3][1], 1.0 / 16.0);
    }
}
