//! Checkpoint and restart.
//!
//! A checkpoint holds everything a step depends on: box, parameters, time step, random key,
//! step counter, positions, momenta, masses, types and ids in storage order, neighbour skin, the Lees-Edwards state
//! (shear rate, offset, travel), the walls with their frozen particles, the body force, the positions and the Lees-Edwards state of the last
//! neighbour-list build (which fix the sweep order and the next rebuild), the name of the
//! scheme, the topology (bonds and angles by id, from version 8), the Lowe-Andersen collision
//! rate (from version 9), whether bonded pairs are excluded from the pair forces (from version
//! 10), PAdL's thermostat mass and adaptive friction factor xi (from version 11), the counts
//! of the accept/reject tests of Metropolis-adjusted schemes (from version 12), PNHL's
//! thermostat friction (from version 13), and what a scheme carries between steps (the full forces of velocity Verlet, with
//! their noise). Pair geometry and conservative forces are not stored: they are pure functions
//! of the positions and the list, recomputed in the same pair order, hence bitwise equal. A restarted run
//! therefore continues bit for bit like an uninterrupted one.
//!
//! File layout: 8 magic bytes `DPDCHKPT`, format version (u32 LE), payload length (u64 LE),
//! CRC-32 of the payload (u32 LE), payload (bincode: the fields of `Payload`, then, from
//! version 8, the optional topology, from version 9 the optional collision rate and from
//! version 10 the exclusion flag, from version 11 the optional thermostat mass and xi, from
//! version 12 the tests made and accepted (two u64), from version 13 the optional thermostat
//! friction; version 7 to 12 files, without them, still load, excluding nothing, with xi = 1,
//! no test counted and no thermostat friction). Writes go to a temporary file in the same
//! directory, are synced, then renamed over the target, so an interrupted write never destroys
//! the previous checkpoint.

use crate::bonded::Topology;
use crate::boundary::{LeesEdwards, PeriodicBox};
use crate::error::CheckpointError;
use crate::params::{Params, ParamsBuilder};
use crate::system::{Continuation, System};
use crate::walls::Walls;
use crate::Vec3;
use serde::{Deserialize, Serialize};
use std::io::Write;
use std::path::Path;

const MAGIC: &[u8; 8] = b"DPDCHKPT";
const VERSION: u32 = 13;
/// The oldest version read: version 7 is version 13 without the topology, the collision rate,
/// the exclusion flag, the thermostat mass and xi, the acceptance counts and the thermostat
/// friction; each later version adds the next of them.
const OLDEST: u32 = 7;
const HEADER: usize = 8 + 4 + 8 + 4;

#[derive(Serialize, Deserialize)]
struct Payload {
    scheme: String,
    params: Params,
    bx: PeriodicBox,
    dt: f64,
    seed: u64,
    step: u64,
    skin: f64,
    q: Vec<Vec3>,
    p: Vec<Vec3>,
    mass: Vec<f64>,
    kind: Vec<u16>,
    /// Particle ids in storage order (the order of the neighbour grid at the last build).
    id: Vec<u32>,
    full_forces: Option<Vec<Vec3>>,
    /// Positions at the last neighbour-list build: the sweep order and the rebuild times
    /// depend on them (empty before the first build).
    list_reference: Vec<Vec3>,
    /// Lees-Edwards `[rate, offset, travel]`, now and at the last neighbour-list build.
    shear: Option<[f64; 3]>,
    list_shear: Option<[f64; 3]>,
    /// Drift since the list last checked the positions (the blow-up guard's bound carries it
    /// into the next step).
    travel: f64,
    /// Walls `[lower, upper, velocity lower, velocity upper]` and the frozen particles.
    walls: Option<([f64; 4], Vec<bool>)>,
    body_force: Option<Vec3>,
}

fn shear_state(le: Option<&LeesEdwards>) -> Option<[f64; 3]> {
    le.map(|le| [le.rate(), le.offset(), le.travel()])
}

fn restore_shear(
    state: Option<[f64; 3]>,
    bx: &PeriodicBox,
) -> Result<Option<LeesEdwards>, crate::ParamError> {
    state
        .map(|[rate, offset, travel]| LeesEdwards::restore(rate, offset, travel, bx))
        .transpose()
}

impl System {
    /// Write a checkpoint of this system, stepped by the scheme named `scheme`, atomically.
    pub fn save_checkpoint(&self, path: &Path, scheme: &str) -> Result<(), CheckpointError> {
        let io = |source| CheckpointError::Io {
            path: path.display().to_string(),
            source,
        };
        let c = self.continuation();
        let payload = Payload {
            scheme: scheme.to_string(),
            params: self.params().clone(),
            bx: *self.boundary(),
            dt: self.dt(),
            seed: self.seed(),
            step: c.step,
            skin: self.skin(),
            q: self.positions().to_vec(),
            p: self.momenta().to_vec(),
            mass: self.masses().to_vec(),
            kind: self.kinds().to_vec(),
            id: self.ids().to_vec(),
            full_forces: c.full_forces,
            list_reference: c.list_reference,
            shear: shear_state(c.shear.as_ref()),
            list_shear: shear_state(c.list_shear.as_ref()),
            travel: c.travel,
            walls: self.walls().zip(self.frozen()).map(|(w, frozen)| {
                let [v0, v1] = w.velocity();
                ([w.lower(), w.upper(), v0, v1], frozen.to_vec())
            }),
            body_force: self.body_force(),
        };
        let encode = |e: bincode::Error| CheckpointError::Decode {
            path: path.display().to_string(),
            message: e.to_string(),
        };
        let mut data = bincode::serialize(&payload).map_err(encode)?;
        bincode::serialize_into(&mut data, &self.topology()).map_err(encode)?;
        bincode::serialize_into(&mut data, &self.params().collision_rate()).map_err(encode)?;
        bincode::serialize_into(&mut data, &self.excludes_bonded()).map_err(encode)?;
        bincode::serialize_into(&mut data, &self.params().thermostat_mass()).map_err(encode)?;
        bincode::serialize_into(&mut data, &self.xi()).map_err(encode)?;
        let acceptance = self.acceptance();
        bincode::serialize_into(&mut data, &(acceptance.proposed, acceptance.accepted))
            .map_err(encode)?;
        bincode::serialize_into(&mut data, &self.params().thermostat_friction()).map_err(encode)?;
        let mut bytes = Vec::with_capacity(HEADER + data.len());
        bytes.extend_from_slice(MAGIC);
        bytes.extend_from_slice(&VERSION.to_le_bytes());
        bytes.extend_from_slice(&(data.len() as u64).to_le_bytes());
        bytes.extend_from_slice(&crc32fast::hash(&data).to_le_bytes());
        bytes.extend_from_slice(&data);

        let mut tmp_name = path.file_name().unwrap_or_default().to_os_string();
        tmp_name.push(format!(".tmp{}", std::process::id()));
        let tmp = path.with_file_name(tmp_name);
        let mut file = std::fs::File::create(&tmp).map_err(io)?;
        file.write_all(&bytes).map_err(io)?;
        file.sync_all().map_err(io)?;
        drop(file);
        std::fs::rename(&tmp, path).map_err(io)
    }

    /// Read a checkpoint; returns the system and the name of the scheme that was stepping it.
    pub fn load_checkpoint(path: &Path) -> Result<(System, String), CheckpointError> {
        let name = path.display().to_string();
        let bytes = std::fs::read(path).map_err(|source| CheckpointError::Io {
            path: name.clone(),
            source,
        })?;
        if bytes.len() < HEADER || &bytes[..8] != MAGIC {
            return Err(
                if bytes.len() < HEADER && MAGIC.starts_with(&bytes[..bytes.len().min(8)]) {
                    CheckpointError::Truncated {
                        path: name,
                        expected: HEADER as u64,
                        found: bytes.len() as u64,
                    }
                } else {
                    CheckpointError::NotACheckpoint { path: name }
                },
            );
        }
        let word = |r: std::ops::Range<usize>| bytes[r].to_vec();
        let version = u32::from_le_bytes(word(8..12).try_into().unwrap_or_default());
        if !(OLDEST..=VERSION).contains(&version) {
            return Err(CheckpointError::Version {
                path: name,
                found: version,
                oldest: OLDEST,
                newest: VERSION,
            });
        }
        let len = u64::from_le_bytes(word(12..20).try_into().unwrap_or_default());
        let crc = u32::from_le_bytes(word(20..24).try_into().unwrap_or_default());
        let data = &bytes[HEADER..];
        if data.len() as u64 != len {
            return Err(CheckpointError::Truncated {
                path: name,
                expected: len,
                found: data.len() as u64,
            });
        }
        if crc32fast::hash(data) != crc {
            return Err(CheckpointError::Corrupt { path: name });
        }
        let decode = |e: bincode::Error| CheckpointError::Decode {
            path: name.clone(),
            message: e.to_string(),
        };
        let mut rest = data;
        let payload: Payload = bincode::deserialize_from(&mut rest).map_err(decode)?;
        let topology: Option<Topology> = if version >= 8 {
            bincode::deserialize_from(&mut rest).map_err(decode)?
        } else {
            None
        };
        let collision_rate: Option<f64> = if version >= 9 {
            bincode::deserialize_from(&mut rest).map_err(decode)?
        } else {
            None
        };
        let exclude_bonded: bool = if version >= 10 {
            bincode::deserialize_from(&mut rest).map_err(decode)?
        } else {
            false
        };
        let (thermostat_mass, xi): (Option<f64>, f64) = if version >= 11 {
            let mass = bincode::deserialize_from(&mut rest).map_err(decode)?;
            (mass, bincode::deserialize_from(&mut rest).map_err(decode)?)
        } else {
            (None, 1.0)
        };
        let (proposed, accepted): (u64, u64) = if version >= 12 {
            bincode::deserialize_from(&mut rest).map_err(decode)?
        } else {
            (0, 0)
        };
        let thermostat_friction: Option<f64> = if version >= 13 {
            bincode::deserialize_from(&mut rest).map_err(decode)?
        } else {
            None
        };
        let invalid = |source| CheckpointError::Invalid {
            path: name.clone(),
            source,
        };
        let params = ParamsBuilder {
            collision_rate,
            thermostat_mass,
            thermostat_friction,
            ..payload.params.into()
        };
        let params = params.build().map_err(invalid)?;
        let shear = restore_shear(payload.shear, &payload.bx).map_err(invalid)?;
        let list_shear = restore_shear(payload.list_shear, &payload.bx).map_err(invalid)?;
        let mut builder = System::builder(params, payload.bx, payload.q)
            .momenta(payload.p)
            .masses(payload.mass)
            .kinds(payload.kind)
            .ids(payload.id)
            .dt(payload.dt)
            .seed(payload.seed)
            .skin(payload.skin);
        if let Some(([lower, upper, v0, v1], frozen)) = payload.walls {
            let walls = Walls::new(lower, upper, [v0, v1]).map_err(invalid)?;
            builder = builder.walls(walls).frozen(frozen);
        }
        if let Some(g) = payload.body_force {
            builder = builder.body_force(g);
        }
        if let Some(t) = topology {
            builder = builder.topology(t).exclude_bonded(exclude_bonded);
        }
        let mut sys = builder.build().map_err(invalid)?;
        sys.set_xi(xi).map_err(invalid)?;
        sys.resume(Continuation {
            step: payload.step,
            shear,
            travel: payload.travel,
            list_reference: payload.list_reference,
            list_shear,
            full_forces: payload.full_forces,
            acceptance: crate::system::Acceptance { proposed, accepted },
        })
        .map_err(invalid)?;
        Ok((sys, payload.scheme))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bonded::{Bond, BondStyle};
    use crate::init::equilibrium_box;

    fn system(topology: Option<Topology>) -> System {
        let b = equilibrium_box(Params::builder().build().unwrap(), 200, 3.0, 3).unwrap();
        match topology {
            Some(t) => b.topology(t).exclude_bonded(true),
            None => b,
        }
        .build()
        .unwrap()
    }

    #[test]
    fn the_topology_is_kept() {
        let mut t = Topology::builder(200);
        t.bond_types = vec![BondStyle::Fene {
            k: 30.0,
            r_max: 4.0,
        }];
        t.bonds = vec![Bond {
            i: 7,
            j: 3,
            kind: 0,
        }];
        let t = t.build().unwrap();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("c.chk");
        let mut sys = system(Some(t.clone()));
        sys.pairs();
        sys.save_checkpoint(&path, "ABOBA").unwrap();
        let (back, _) = System::load_checkpoint(&path).unwrap();
        assert_eq!(back.topology(), Some(&t));
        assert!(back.excludes_bonded());
        assert_eq!(back.ids(), sys.ids());
    }

    /// Version 7 to 12 files (version 13 without the topology, the collision rate, the
    /// exclusion flag, the thermostat mass, xi, the acceptance counts and the thermostat
    /// friction that follow the payload, or without the first of them that their version
    /// lacks) load, excluding nothing, with xi = 1, no test counted and no friction.
    #[test]
    fn version_7_to_12_checkpoints_load() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("c.chk");
        let sys = system(None);
        sys.save_checkpoint(&path, "ABOBA").unwrap();
        let bytes = std::fs::read(&path).unwrap();
        let mut tail = vec![0, 0, 0, 0];
        tail.extend_from_slice(&1f64.to_le_bytes());
        tail.extend_from_slice(&[0; 17]);
        assert_eq!(
            bytes[bytes.len() - 29..],
            tail,
            "bincode's None twice, false, None, xi = 1, no test, None"
        );
        for (version, dropped) in [(7u32, 29), (8, 28), (9, 27), (10, 26), (11, 17), (12, 1)] {
            let data = &bytes[HEADER..bytes.len() - dropped];
            let mut old = MAGIC.to_vec();
            old.extend_from_slice(&version.to_le_bytes());
            old.extend_from_slice(&(data.len() as u64).to_le_bytes());
            old.extend_from_slice(&crc32fast::hash(data).to_le_bytes());
            old.extend_from_slice(data);
            std::fs::write(&path, old).unwrap();
            let (back, scheme) = System::load_checkpoint(&path).unwrap();
            assert_eq!(
                (back.positions(), scheme.as_str()),
                (sys.positions(), "ABOBA")
            );
            assert!(back.topology().is_none() && back.params().collision_rate().is_none());
            assert!(!back.excludes_bonded() && back.params().thermostat_mass().is_none());
            assert_eq!(back.xi(), 1.0);
            assert_eq!(back.acceptance(), Default::default());
        }
    }

    /// The thermostat mass, PNHL's thermostat friction and the adaptive friction factor are
    /// kept.
    #[test]
    fn the_adaptive_thermostat_is_kept() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("c.chk");
        let params = Params::builder()
            .thermostat_mass(10.0)
            .thermostat_friction(2.0);
        let params = params.build().unwrap();
        let mut sys = equilibrium_box(params, 200, 3.0, 3)
            .unwrap()
            .build()
            .unwrap();
        sys.set_xi(0.8125).unwrap();
        sys.save_checkpoint(&path, "B A Xi(1/2) On Xi(1/2) A B")
            .unwrap();
        let (back, _) = System::load_checkpoint(&path).unwrap();
        assert_eq!((back.params(), back.xi()), (sys.params(), 0.8125));
    }

    /// The collision rate of Lowe-Andersen schemes is kept.
    #[test]
    fn the_collision_rate_is_kept() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("c.chk");
        let params = Params::builder().collision_rate(2.5).build().unwrap();
        let sys = equilibrium_box(params, 200, 3.0, 3)
            .unwrap()
            .build()
            .unwrap();
        sys.save_checkpoint(&path, "B A B L").unwrap();
        let (back, _) = System::load_checkpoint(&path).unwrap();
        assert_eq!(back.params(), sys.params());
    }
}
