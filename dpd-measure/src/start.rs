//! Runs started from a frame of a GSD file (`init = "FILE.gsd[:frame]"`, `--init`), read by
//! the `dpd-trajectory` crate.

use dpd_core::{ParamError, Vec3};
use dpd_trajectory::gsd::GsdReader;
use dpd_trajectory::Frame;
use std::path::PathBuf;

/// `init = "FILE.gsd[:frame]"`: the file and the frame (default: the last).
#[derive(Clone, Debug, PartialEq)]
pub struct InitSpec {
    pub file: PathBuf,
    pub frame: Option<u64>,
}

impl InitSpec {
    /// Parse `FILE.gsd` or `FILE.gsd:K`.
    pub fn parse(text: &str) -> Result<InitSpec, ParamError> {
        let (file, frame) = match text.rsplit_once(':') {
            Some((file, k)) if file.ends_with(".gsd") => {
                let k = k.parse().map_err(|_| {
                    ParamError::new(
                        "init",
                        text,
                        "the frame after ':' must be a whole number >= 0",
                    )
                })?;
                (file, Some(k))
            }
            _ => (text, None),
        };
        if !file.ends_with(".gsd") {
            return Err(ParamError::new(
                "init",
                text,
                "must be a GSD file, FILE.gsd or FILE.gsd:frame",
            ));
        }
        Ok(InitSpec {
            file: PathBuf::from(file),
            frame,
        })
    }

    /// The frame, checked against the scene's particle count and box.
    pub fn read(&self, n: usize, box_lengths: [f64; 3]) -> Result<Frame, ParamError> {
        let bad = |message: String| ParamError::new("init", self.file.display(), message);
        let reader = GsdReader::open(&self.file).map_err(|e| bad(e.to_string()))?;
        let k = match self.frame {
            Some(k) => k,
            None if reader.frames() > 0 => reader.frames() - 1,
            None => return Err(bad("the file has no frame".into())),
        };
        let f = reader.frame(k).map_err(|e| bad(e.to_string()))?;
        if f.len() != n {
            return Err(bad(format!(
                "frame {k} has {} particles, the scene {n}: set n (or box and density) to match",
                f.len()
            )));
        }
        let mismatch = |a: f64, b: f64| (a - b).abs() > 1e-5 * b.abs();
        if (0..3).any(|d| mismatch(f.box_lengths[d], box_lengths[d])) {
            return Err(bad(format!(
                "frame {k} has box {:?}, the scene {box_lengths:?}: set box (or n and density) \
                 to match",
                f.box_lengths
            )));
        }
        Ok(f)
    }
}

/// Positions, momenta, masses (`mass` where the file has none) and types of `f` for a system
/// of `types` particle types.
pub type InitialState = (Vec<Vec3>, Vec<Vec3>, Vec<f64>, Vec<u16>);

pub fn initial_state(f: &Frame, mass: f64, types: usize) -> Result<InitialState, ParamError> {
    if let Some(i) = f.typeid.iter().position(|&t| t as usize >= types) {
        return Err(ParamError::new(
            format!("init: typeid of particle {i}"),
            f.typeid[i],
            format!(
                "the scene has {types} particle type(s): type ids 0 to {}",
                types - 1
            ),
        ));
    }
    let to = |v: &[f64; 3]| Vec3::new(v[0], v[1], v[2]);
    let masses = f.masses.clone().unwrap_or_else(|| vec![mass; f.len()]);
    let q = f.positions.iter().map(to).collect();
    let p = match &f.velocities {
        Some(v) => v.iter().zip(&masses).map(|(v, m)| to(v) * *m).collect(),
        None => vec![Vec3::zeros(); f.len()],
    };
    let kinds = f.typeid.iter().map(|&t| t as u16).collect();
    Ok((q, p, masses, kinds))
}
