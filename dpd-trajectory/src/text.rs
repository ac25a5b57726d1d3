//! The text formats: extended XYZ and LAMMPS dump text. A frame is formatted in memory and
//! appended with one write, so a run stopped between frames (Ctrl-C, or a kill while the next
//! frame is being computed) leaves whole frames only; a kill landing inside that one write can
//! cut the last frame short, which GSD's commit (see [`crate::gsd`]) rules out.

use super::{Format, Frame, TrajectoryError};
use std::fmt::Write as _;
use std::fs::File;
use std::io::Write as _;
use std::path::{Path, PathBuf};

pub struct TextWriter {
    file: File,
    path: PathBuf,
    format: Format,
}

impl TextWriter {
    pub fn create(path: &Path, format: Format) -> Result<TextWriter, TrajectoryError> {
        let file = File::create(path).map_err(TrajectoryError::io(path))?;
        Ok(TextWriter {
            file,
            path: path.to_path_buf(),
            format,
        })
    }

    pub fn append(&mut self, frame: &Frame) -> Result<(), TrajectoryError> {
        let text = match self.format {
            Format::LammpsDump => lammps_dump(frame),
            _ => extended_xyz(frame),
        };
        self.file
            .write_all(text.as_bytes())
            .map_err(TrajectoryError::io(&self.path))
    }
}

/// One extended-XYZ block: the count, a comment line of `key=value` pairs (`Lattice`,
/// `Properties`, `pbc`, `step`, `time`, `dt` and the log values), then a line per particle.
///
/// The columns are named for their readers: `species` (the type name: OVITO's particle type,
/// MDAnalysis's atom name) and `pos` come first, as plain-XYZ readers such as MDAnalysis take
/// the name and the next three numbers; `velo` and `mass` are OVITO's names for velocity and
/// mass; `momenta` and `masses` are ASE's (its `get_velocities` is momenta / masses, so masses
/// go with velocities); `Z` (type index + 1) comes last, because ASE builds atoms from element
/// numbers and refuses a type name like "A" (it reads type A as hydrogen).
fn extended_xyz(f: &Frame) -> String {
    let [lx, ly, lz] = f.box_lengths;
    let masses = f
        .masses
        .clone()
        .or_else(|| f.velocities.as_ref().map(|_| vec![1.0; f.len()]));
    let mut props = String::from("species:S:1:pos:R:3");
    if f.velocities.is_some() {
        props += ":velo:R:3:momenta:R:3";
    }
    if masses.is_some() {
        props += ":mass:R:1:masses:R:1";
    }
    props += ":Z:I:1";
    let mut out = format!(
        "{}\nLattice=\"{lx} 0 0 0 {ly} 0 0 0 {lz}\" Properties={props} pbc=\"T T T\" step={} \
         time={} dt={}",
        f.len(),
        f.step,
        f.time,
        f.dt
    );
    for (name, value) in &f.log {
        let _ = write!(out, " {}={value}", name.replace([' ', '='], "_"));
    }
    out.push('\n');
    for (i, q) in f.positions.iter().enumerate() {
        let _ = write!(out, "{} {} {} {}", f.type_name(i), q[0], q[1], q[2]);
        if let Some(v) = &f.velocities {
            let m = masses.as_ref().map_or(1.0, |m| m[i]);
            let [x, y, z] = v[i];
            let _ = write!(out, " {x} {y} {z} {} {} {}", m * x, m * y, m * z);
        }
        if let Some(m) = &masses {
            let _ = write!(out, " {} {}", m[i], m[i]);
        }
        let _ = writeln!(out, " {}", f.typeid[i] + 1);
    }
    out
}

/// One LAMMPS dump block: `ITEM: TIMESTEP`, the count, the periodic box `0 L` per axis and a
/// line per particle with id and type counted from 1 (LAMMPS's convention).
fn lammps_dump(f: &Frame) -> String {
    let mut out = format!(
        "ITEM: TIMESTEP\n{}\nITEM: NUMBER OF ATOMS\n{}\nITEM: BOX BOUNDS pp pp pp\n",
        f.step,
        f.len()
    );
    for l in f.box_lengths {
        let _ = writeln!(out, "0 {l}");
    }
    out += "ITEM: ATOMS id type x y z";
    if f.velocities.is_some() {
        out += " vx vy vz";
    }
    if f.images.is_some() {
        out += " ix iy iz";
    }
    if f.masses.is_some() {
        out += " mass";
    }
    out.push('\n');
    for (i, q) in f.positions.iter().enumerate() {
        let _ = write!(
            out,
            "{} {} {} {} {}",
            i + 1,
            f.typeid[i] + 1,
            q[0],
            q[1],
            q[2]
        );
        if let Some(v) = &f.velocities {
            let _ = write!(out, " {} {} {}", v[i][0], v[i][1], v[i][2]);
        }
        if let Some(im) = &f.images {
            let _ = write!(out, " {} {} {}", im[i][0], im[i][1], im[i][2]);
        }
        if let Some(m) = &f.masses {
            let _ = write!(out, " {}", m[i]);
        }
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two() -> Frame {
        Frame {
            step: 7,
            time: 0.35,
            dt: 0.05,
            box_lengths: [2.0, 3.0, 4.0],
            positions: vec![[0.5, 1.0, 1.5], [1.5, 2.5, 3.5]],
            velocities: Some(vec![[0.1, 0.2, 0.3], [-0.1, -0.2, -0.3]]),
            images: None,
            typeid: vec![0, 1],
            types: vec!["A".into(), "W".into()],
            masses: None,
            log: vec![("kinetic_temperature".into(), 1.25)],
            bonds: None,
        }
    }

    #[test]
    fn extended_xyz_names_the_columns_for_their_readers() {
        let text = extended_xyz(&two());
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 4);
        assert_eq!(lines[0], "2");
        assert!(lines[1].starts_with("Lattice=\"2 0 0 0 3 0 0 0 4\""));
        assert!(lines[1].contains(
            "Properties=species:S:1:pos:R:3:velo:R:3:momenta:R:3:mass:R:1:masses:R:1:Z:I:1 "
        ));
        assert!(lines[1].ends_with("step=7 time=0.35 dt=0.05 kinetic_temperature=1.25"));
        // Without masses in the frame, velocities come with the unit mass.
        assert_eq!(
            lines[3],
            "W 1.5 2.5 3.5 -0.1 -0.2 -0.3 -0.1 -0.2 -0.3 1 1 2"
        );
        let heavy = Frame {
            masses: Some(vec![1.0, 2.0]),
            ..two()
        };
        let text = extended_xyz(&heavy);
        assert_eq!(
            text.lines().nth(3),
            Some("W 1.5 2.5 3.5 -0.1 -0.2 -0.3 -0.2 -0.4 -0.6 2 2 2")
        );
        let still = Frame {
            velocities: None,
            ..two()
        };
        let text = extended_xyz(&still);
        assert!(
            text.contains("Properties=species:S:1:pos:R:3:Z:I:1 "),
            "{text}"
        );
        assert_eq!(text.lines().nth(2), Some("A 0.5 1 1.5 1"));
    }

    #[test]
    fn lammps_dump_counts_ids_and_types_from_one() {
        let text = lammps_dump(&two());
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[1], "7");
        assert_eq!(lines[3], "2");
        assert_eq!(lines[5..8], ["0 2", "0 3", "0 4"]);
        assert_eq!(lines[8], "ITEM: ATOMS id type x y z vx vy vz");
        assert_eq!(lines[10], "2 2 1.5 2.5 3.5 -0.1 -0.2 -0.3");
    }
}
