//! Periodic images of a run's particles, followed step by step, so that a trajectory's wrapped
//! positions can be unwrapped by its readers (GSD `particles/image`, the dumps' `ix iy iz`):
//! the unwrapped position of particle `i` is `position_i + image_i * L` (componentwise).

use dpd_core::{ParamError, System, Vec3};

/// How many times each particle, by id, has crossed each pair of box faces since the tracker
/// started (+1 for a crossing in the positive direction).
///
/// Updated after every step from the change of the wrapped positions: a change of more than half
/// an edge is a crossing. Exact as long as no particle moves half an edge in one step (an edge is
/// at least 2 r_c, so a particle would need to travel r_c in one step; such a run is far past
/// any stable time step). Under walls the z axis is not periodic and its image stays 0.
#[derive(Clone, Debug)]
pub struct Images {
    /// Wrapped positions by id at the last update.
    last: Vec<Vec3>,
    /// Images by id.
    image: Vec<[i32; 3]>,
}

impl Images {
    /// Start from the system's current positions with the images `initial` (by id; `None`:
    /// every image 0). Lees-Edwards boundaries are refused: a particle crossing the sliding
    /// faces also moves by the boundaries' offset along x, which an image count cannot express.
    pub fn start(sys: &System, initial: Option<&[[i32; 3]]>) -> Result<Images, ParamError> {
        if let Some(le) = sys.shear() {
            return Err(ParamError::new(
                "trajectory.fields",
                "image",
                format!(
                    "is not defined under Lees-Edwards boundaries (shear rate {}): leave \
                     \"image\" out of fields",
                    le.rate()
                ),
            ));
        }
        let n = sys.positions().len();
        let mut last = vec![Vec3::zeros(); n];
        for (q, &id) in sys.positions().iter().zip(sys.ids()) {
            last[id as usize] = *q;
        }
        let image = match initial {
            Some(images) if images.len() == n => images.to_vec(),
            Some(images) => {
                return Err(ParamError::new(
                    "init",
                    format!("{} images", images.len()),
                    format!("the frame's images must be one per particle ({n})"),
                ))
            }
            None => vec![[0; 3]; n],
        };
        Ok(Images { last, image })
    }

    /// Count the crossings of the step just taken.
    pub fn update(&mut self, sys: &System) {
        let half = 0.5 * sys.boundary().lengths();
        for (q, &id) in sys.positions().iter().zip(sys.ids()) {
            let i = id as usize;
            let d = q - self.last[i];
            for k in 0..3 {
                if d[k] > half[k] {
                    self.image[i][k] -= 1;
                } else if d[k] < -half[k] {
                    self.image[i][k] += 1;
                }
            }
            self.last[i] = *q;
        }
    }

    /// The images by id.
    pub fn by_id(&self) -> &[[i32; 3]] {
        &self.image
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use dpd_core::flow::drift;
    use dpd_core::init::{cubic_box, maxwell_momenta, uniform_positions};
    use dpd_core::Params;

    fn free_particles(shear: Option<f64>) -> System {
        let n = 200;
        let bx = cubic_box(n, 3.0).unwrap();
        let q = uniform_positions(&bx, n, 5);
        // k_B T = 4: speeds of 2 to 6, each particle crossing the 4.05-wide box many times.
        let p = maxwell_momenta(&vec![1.0; n], 4.0, 5);
        let b = System::builder(Params::builder().build().unwrap(), bx, q).momenta(p);
        match shear {
            Some(kappa) => b.shear_rate(kappa),
            None => b,
        }
        .build()
        .unwrap()
    }

    /// Free flight (drifts only): the unwrapped position must be q0 + (p / m) t for every
    /// particle, which a missed, doubled or wrong-signed crossing would change by a box edge.
    #[test]
    fn unwrapped_free_flight_is_the_straight_line() {
        let mut sys = free_particles(None);
        let by_id = |sys: &System| {
            let mut v = vec![(Vec3::zeros(), Vec3::zeros()); sys.positions().len()];
            for ((q, p), &id) in sys.positions().iter().zip(sys.momenta()).zip(sys.ids()) {
                v[id as usize] = (*q, *p);
            }
            v
        };
        let start = by_id(&sys);
        let mut images = Images::start(&sys, None).unwrap();
        let (h, steps) = (0.1, 400);
        for _ in 0..steps {
            drift(&mut sys, h);
            images.update(&sys);
        }
        let l = sys.boundary().lengths();
        let t = h * steps as f64;
        let mut crossings = 0;
        for (i, (q, _)) in by_id(&sys).iter().enumerate() {
            let image = Vec3::from(images.by_id()[i].map(f64::from));
            let unwrapped = q + image.component_mul(&l);
            let expected = start[i].0 + start[i].1 * t;
            assert!(
                (unwrapped - expected).norm() < 1e-9,
                "particle {i}: unwrapped {unwrapped:?}, expected {expected:?}"
            );
            crossings += images.by_id()[i].iter().map(|c| c.abs()).sum::<i32>();
        }
        assert!(
            crossings > 1000,
            "only {crossings} crossings: the test tests little"
        );
    }

    #[test]
    fn lees_edwards_boundaries_are_refused_with_the_reason() {
        let e = Images::start(&free_particles(Some(0.2)), None).unwrap_err();
        assert!(e.to_string().contains("Lees-Edwards"), "{e}");
    }
}
