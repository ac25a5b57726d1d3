//! LAMMPS data files (`read_data` / `write_data`): the header counts and box, `Atom Type
//! Labels`, `Masses`,
//! `Atoms` in the atom styles atomic, bond, molecular and full, `Velocities`, `Bonds`,
//! `Angles`, and the coefficient sections `Pair Coeffs`, `PairIJ Coeffs`, `Bond Coeffs`,
//! `Angle Coeffs` as numbers with the style their comment names (`Pair Coeffs # dpd`). What
//! the coefficients mean is the reader's business: this module keeps them as written.
//!
//! Types and ids count from 1 as in the file. Errors name the line and the section.

use crate::TrajectoryError;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;
use std::iter::Peekable;
use std::path::Path;

/// The columns of the `Atoms` section.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AtomStyle {
    /// `id type x y z`
    Atomic,
    /// `id molecule type x y z`
    Bond,
    /// `id molecule type x y z`
    Molecular,
    /// `id molecule type q x y z`
    Full,
}

impl AtomStyle {
    /// The style's name in LAMMPS.
    pub fn name(self) -> &'static str {
        match self {
            AtomStyle::Atomic => "atomic",
            AtomStyle::Bond => "bond",
            AtomStyle::Molecular => "molecular",
            AtomStyle::Full => "full",
        }
    }

    fn named(name: &str) -> Option<AtomStyle> {
        [
            AtomStyle::Atomic,
            AtomStyle::Bond,
            AtomStyle::Molecular,
            AtomStyle::Full,
        ]
        .into_iter()
        .find(|s| s.name() == name)
    }

    /// Columns before the image flags.
    fn columns(self) -> usize {
        match self {
            AtomStyle::Atomic => 5,
            AtomStyle::Bond | AtomStyle::Molecular => 6,
            AtomStyle::Full => 7,
        }
    }

    /// The style a line of `n` columns has (with or without three image flags), where the
    /// section's comment does not name it: the column counts 5 to 10 are all distinct.
    fn of_columns(n: usize) -> Option<AtomStyle> {
        match n {
            5 | 8 => Some(AtomStyle::Atomic),
            6 | 9 => Some(AtomStyle::Molecular),
            7 | 10 => Some(AtomStyle::Full),
            _ => None,
        }
    }
}

/// One atom of the `Atoms` section, with its velocity.
#[derive(Clone, Debug, PartialEq)]
pub struct Atom {
    pub id: u64,
    /// Molecule id (not in the atomic style).
    pub molecule: Option<u64>,
    /// Atom type, from 1.
    pub kind: u32,
    /// Charge (the full style only).
    pub charge: Option<f64>,
    pub position: [f64; 3],
    /// Image flags (0 where the file has none).
    pub image: [i32; 3],
    /// From the `Velocities` section.
    pub velocity: Option<[f64; 3]>,
}

/// A bond (two atom ids) or an angle (three) with its type, from 1.
#[derive(Clone, Debug, PartialEq)]
pub struct Topology<const K: usize> {
    pub id: u64,
    pub kind: u32,
    pub atoms: [u64; K],
}

/// The numbers of a coefficient section and the style its comment names.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Coeffs<K: Ord> {
    pub style: Option<String>,
    pub by_type: BTreeMap<K, Vec<f64>>,
}

/// A LAMMPS data file, as written.
#[derive(Clone, Debug, PartialEq)]
pub struct DataFile {
    /// The first line.
    pub title: String,
    /// `[lo, hi]` along x, y, z (orthogonal boxes only).
    pub bounds: [[f64; 2]; 3],
    pub atom_types: u32,
    pub bond_types: u32,
    pub angle_types: u32,
    pub atom_style: AtomStyle,
    /// Mass of each atom type (index type - 1), `None` where `Masses` gives none.
    pub masses: Vec<Option<f64>>,
    /// Name of each atom type (`Atom Type Labels`), or `None` without that section.
    pub type_labels: Option<Vec<String>>,
    /// In the order of the file.
    pub atoms: Vec<Atom>,
    pub bonds: Vec<Topology<2>>,
    pub angles: Vec<Topology<3>>,
    /// By type pair `(i, j)`, `i <= j`: `Pair Coeffs` gives `(i, i)`, `PairIJ Coeffs` any.
    pub pair_coeffs: Coeffs<(u32, u32)>,
    pub bond_coeffs: Coeffs<u32>,
    pub angle_coeffs: Coeffs<u32>,
}

/// The sections this reader knows.
const SECTIONS: [&str; 10] = [
    "Atom Type Labels",
    "Masses",
    "Atoms",
    "Velocities",
    "Bonds",
    "Angles",
    "Pair Coeffs",
    "PairIJ Coeffs",
    "Bond Coeffs",
    "Angle Coeffs",
];

/// A line of the file: its number (from 1), its text without the comment, the comment, and
/// the section it belongs to ("" in the header).
struct Line<'a> {
    number: usize,
    text: &'a str,
    comment: &'a str,
    section: &'a str,
}

impl DataFile {
    /// Read `path`.
    pub fn read(path: &Path) -> Result<DataFile, TrajectoryError> {
        let text = std::fs::read_to_string(path).map_err(TrajectoryError::io(path))?;
        DataFile::parse(&text).map_err(|message| TrajectoryError::Format {
            path: path.to_path_buf(),
            message,
        })
    }

    /// Write it to `path`.
    pub fn write(&self, path: &Path) -> Result<(), TrajectoryError> {
        std::fs::write(path, self.to_text()).map_err(TrajectoryError::io(path))
    }

    /// The atom count and the box bounds of the file at `path`, from its header alone (its
    /// sections are neither parsed nor checked): what sizes a system before the file is read.
    pub fn read_size(path: &Path) -> Result<(usize, [[f64; 2]; 3]), TrajectoryError> {
        let text = std::fs::read_to_string(path).map_err(TrajectoryError::io(path))?;
        let (title, mut lines) = lines(&text);
        // The header, and what ends it: a section read here or the end of the file.
        let header = DataFile::header(title, &mut lines).and_then(|header| {
            let end = lines.peek().map_or(Ok(""), section_name);
            end.map(|_| header)
        });
        let (file, counts) = header.map_err(|message| TrajectoryError::Format {
            path: path.to_path_buf(),
            message,
        })?;
        Ok((counts.atoms, file.bounds))
    }

    /// The coefficient sections (`Pair Coeffs`, `PairIJ Coeffs`, `Bond Coeffs`, `Angle
    /// Coeffs`) of the file at `path`, each as its heading with the style comment and its lines
    /// as written, the other sections skipped unread: what a header can say of a file before
    /// a run reads it in full.
    pub fn coefficient_lines(path: &Path) -> Result<Vec<(String, Vec<String>)>, TrajectoryError> {
        let text = std::fs::read_to_string(path).map_err(TrajectoryError::io(path))?;
        let mut sections: Vec<(String, Vec<String>)> = Vec::new();
        let mut inside = false;
        for l in lines(&text).1 {
            if is_section(l.text) {
                inside = l.text.ends_with(" Coeffs");
                if inside {
                    let heading = match l.comment {
                        "" => l.text.to_string(),
                        style => format!("{} # {style}", l.text),
                    };
                    sections.push((heading, Vec::new()));
                }
            } else if let Some((_, body)) = sections.last_mut().filter(|_| inside) {
                body.push(l.text.to_string());
            }
        }
        Ok(sections)
    }

    /// Parse the text of a data file; the error names the line and section.
    pub fn parse(text: &str) -> Result<DataFile, String> {
        let (title, mut lines) = lines(text);
        let (mut file, counts) = DataFile::header(title, &mut lines)?;
        file.masses = vec![None; file.atom_types as usize];
        let mut seen = Vec::new();
        while let Some(head) = lines.next() {
            let name = section_name(&head)?;
            if seen.contains(&name) {
                return Err(format!(
                    "line {}: section `{name}` a second time",
                    head.number
                ));
            }
            seen.push(name);
            let mut body = Vec::new();
            while let Some(line) = lines.next_if(|l| !is_section(l.text)) {
                body.push(Line {
                    section: name,
                    ..line
                });
            }
            let at = |what: &str| format!("section `{name}` (line {}): {what}", head.number);
            let expected = counts.rows(name, &file);
            if body.len() < expected {
                // A line of the section that starts with a letter ended it early: name it.
                if let Some(next) = lines.peek().filter(|l| section_name(l).is_err()) {
                    return Err(not_a_number(&Line {
                        section: name,
                        ..*next
                    }));
                }
            }
            if body.len() != expected {
                return Err(at(&format!(
                    "{} lines, the header asks for {expected}",
                    body.len()
                )));
            }
            file.section(name, head.comment, &body)?;
        }
        file.check(&counts)?;
        Ok(file)
    }

    /// The title line and the header (counts, types, box bounds) up to the first section:
    /// a file with those set and its sections empty, and the section lengths they ask for.
    fn header<'a>(
        title: &str,
        lines: &mut Peekable<impl Iterator<Item = Line<'a>>>,
    ) -> Result<(DataFile, Header), String> {
        let mut file = DataFile {
            title: title.to_string(),
            bounds: [[0.0; 2]; 3],
            atom_types: 0,
            bond_types: 0,
            angle_types: 0,
            atom_style: AtomStyle::Atomic,
            masses: Vec::new(),
            type_labels: None,
            atoms: Vec::new(),
            bonds: Vec::new(),
            angles: Vec::new(),
            pair_coeffs: Coeffs::default(),
            bond_coeffs: Coeffs::default(),
            angle_coeffs: Coeffs::default(),
        };
        let mut counts = Header::default();
        while let Some(line) = lines.next_if(|l| !is_section(l.text)) {
            counts.read(&line, &mut file)?;
        }
        Ok((file, counts))
    }

    /// The text of the file, in the order `write_data` uses; numbers as Rust prints them
    /// (the shortest text that reads back to the same `f64`).
    pub fn to_text(&self) -> String {
        let mut s = String::new();
        let mut w = |line: String| {
            s.push_str(&line);
            s.push('\n');
        };
        w(self.title.clone());
        w(String::new());
        w(format!("{} atoms", self.atoms.len()));
        w(format!("{} atom types", self.atom_types));
        if self.bond_types > 0 || !self.bonds.is_empty() {
            w(format!("{} bonds", self.bonds.len()));
            w(format!("{} bond types", self.bond_types));
        }
        if self.angle_types > 0 || !self.angles.is_empty() {
            w(format!("{} angles", self.angles.len()));
            w(format!("{} angle types", self.angle_types));
        }
        for (b, axis) in self.bounds.iter().zip(["x", "y", "z"]) {
            w(format!("{} {} {axis}lo {axis}hi", b[0], b[1]));
        }
        if let Some(labels) = &self.type_labels {
            w("\nAtom Type Labels\n".into());
            for (t, label) in labels.iter().enumerate() {
                w(format!("{} {label}", t + 1));
            }
        }
        if self.masses.iter().any(Option::is_some) {
            w("\nMasses\n".into());
            for (t, m) in self.masses.iter().enumerate() {
                if let Some(m) = m {
                    w(format!("{} {m}", t + 1));
                }
            }
        }
        let style = |c: &Option<String>| c.as_ref().map_or(String::new(), |s| format!(" # {s}"));
        if !self.pair_coeffs.by_type.is_empty() {
            w(format!(
                "\nPairIJ Coeffs{}\n",
                style(&self.pair_coeffs.style)
            ));
            for ((i, j), c) in &self.pair_coeffs.by_type {
                w(format!("{i} {j} {}", joined(c)));
            }
        }
        for (name, coeffs) in [
            ("Bond Coeffs", &self.bond_coeffs),
            ("Angle Coeffs", &self.angle_coeffs),
        ] {
            if !coeffs.by_type.is_empty() {
                w(format!("\n{name}{}\n", style(&coeffs.style)));
                for (t, c) in &coeffs.by_type {
                    w(format!("{t} {}", joined(c)));
                }
            }
        }
        w(format!("\nAtoms # {}\n", self.atom_style.name()));
        for a in &self.atoms {
            let mut line = a.id.to_string();
            if let Some(m) = a.molecule {
                let _ = write!(line, " {m}");
            }
            let _ = write!(line, " {}", a.kind);
            if let Some(q) = a.charge {
                let _ = write!(line, " {q}");
            }
            let [x, y, z] = a.position;
            let [i, j, k] = a.image;
            let _ = write!(line, " {x} {y} {z} {i} {j} {k}");
            w(line);
        }
        if self.atoms.iter().any(|a| a.velocity.is_some()) {
            w("\nVelocities\n".into());
            for a in &self.atoms {
                let [x, y, z] = a.velocity.unwrap_or_default();
                w(format!("{} {x} {y} {z}", a.id));
            }
        }
        if !self.bonds.is_empty() {
            w("\nBonds\n".into());
            for b in &self.bonds {
                w(format!("{} {} {} {}", b.id, b.kind, b.atoms[0], b.atoms[1]));
            }
        }
        if !self.angles.is_empty() {
            w("\nAngles\n".into());
            for a in &self.angles {
                let [i, j, k] = a.atoms;
                w(format!("{} {} {i} {j} {k}", a.id, a.kind));
            }
        }
        s
    }

    /// Read the body of section `name` (whose comment is `comment`).
    fn section(&mut self, name: &str, comment: &str, body: &[Line]) -> Result<(), String> {
        let style = (!comment.is_empty()).then(|| comment.to_string());
        match name {
            "Atom Type Labels" => {
                let mut labels = vec![String::new(); self.atom_types as usize];
                for l in body {
                    let t = type_in(l, 0, self.atom_types, "atom")?;
                    let words: Vec<&str> = l.text.split_whitespace().collect();
                    if words.len() != 2 || words[1].starts_with(|c: char| c.is_ascii_digit()) {
                        return Err(at(
                            l,
                            "a type label line is `type label`, the label not a number",
                        ));
                    }
                    labels[t as usize - 1] = words[1].to_string();
                }
                self.type_labels = Some(labels);
            }
            "Masses" => {
                for l in body {
                    let (t, v) = (type_in(l, 0, self.atom_types, "atom")?, floats(l, 1..)?);
                    if v.len() != 1 || !(v[0].is_finite() && v[0] > 0.0) {
                        return Err(at(l, "a mass line is `type mass` with mass finite and > 0"));
                    }
                    self.masses[t as usize - 1] = Some(v[0]);
                }
            }
            "Atoms" => {
                if let Some(s) = style.as_deref() {
                    self.atom_style = AtomStyle::named(s).ok_or_else(|| {
                        format!(
                            "section `Atoms`: atom style `{s}` is not read here (atomic, bond, \
                             molecular, full)"
                        )
                    })?;
                } else if let Some(first) = body.first() {
                    let n = first.text.split_whitespace().count();
                    self.atom_style = AtomStyle::of_columns(n).ok_or_else(|| {
                        at(first, &format!("{n} columns are no atom style read here"))
                    })?;
                }
                let mut ids = BTreeSet::new();
                for l in body {
                    let atom = self.atom(l)?;
                    if !ids.insert(atom.id) {
                        return Err(format!(
                            "section `Atoms`: atom id {} appears twice",
                            atom.id
                        ));
                    }
                    self.atoms.push(atom);
                }
            }
            "Velocities" => {
                let index: BTreeMap<u64, usize> = self
                    .atoms
                    .iter()
                    .enumerate()
                    .map(|(k, a)| (a.id, k))
                    .collect();
                if self.atoms.is_empty() {
                    return Err("section `Velocities`: comes before `Atoms`".into());
                }
                for l in body {
                    let v = floats(l, 1..)?;
                    let id = integer(l, 0, "atom id")?;
                    let k = *index
                        .get(&id)
                        .ok_or_else(|| at(l, &format!("atom {id} is not in Atoms")))?;
                    if v.len() != 3 {
                        return Err(at(l, "a velocity line is `id vx vy vz`"));
                    }
                    self.atoms[k].velocity = Some([v[0], v[1], v[2]]);
                }
            }
            "Bonds" | "Angles" => {
                if self.atoms.is_empty() {
                    return Err(format!("section `{name}`: comes before `Atoms`"));
                }
                let ids: BTreeSet<u64> = self.atoms.iter().map(|a| a.id).collect();
                for l in body {
                    if name == "Bonds" {
                        let (id, kind, atoms) = self.topology(l, &ids, self.bond_types, "bond")?;
                        self.bonds.push(Topology { id, kind, atoms });
                    } else {
                        let (id, kind, atoms) =
                            self.topology(l, &ids, self.angle_types, "angle")?;
                        self.angles.push(Topology { id, kind, atoms });
                    }
                }
            }
            "Pair Coeffs" | "PairIJ Coeffs" => {
                let both = name == "PairIJ Coeffs";
                self.pair_coeffs.style = style;
                for l in body {
                    let i = type_in(l, 0, self.atom_types, "atom")?;
                    let j = match both {
                        true => type_in(l, 1, self.atom_types, "atom")?,
                        false => i,
                    };
                    let pair = (i.min(j), i.max(j));
                    let c = floats(l, if both { 2.. } else { 1.. })?;
                    if self.pair_coeffs.by_type.insert(pair, c).is_some() {
                        return Err(at(
                            l,
                            &format!("the pair {} {} a second time", pair.0, pair.1),
                        ));
                    }
                }
            }
            _ => {
                let (types, coeffs, what) = match name {
                    "Bond Coeffs" => (self.bond_types, &mut self.bond_coeffs, "bond"),
                    _ => (self.angle_types, &mut self.angle_coeffs, "angle"),
                };
                coeffs.style = style;
                for l in body {
                    let t = type_in(l, 0, types, what)?;
                    coeffs.by_type.insert(t, floats(l, 1..)?);
                }
            }
        }
        Ok(())
    }

    fn atom(&self, l: &Line) -> Result<Atom, String> {
        let style = self.atom_style;
        let words: Vec<&str> = l.text.split_whitespace().collect();
        let n = style.columns();
        if words.len() != n && words.len() != n + 3 {
            return Err(at(
                l,
                &format!(
                    "{} columns; atom style {} has {n} (or {} with image flags)",
                    words.len(),
                    style.name(),
                    n + 3
                ),
            ));
        }
        let molecular = style != AtomStyle::Atomic;
        let kind_column = 1 + usize::from(molecular);
        let xyz = floats(l, n - 3..n)?;
        let image = match words.len() > n {
            true => {
                let mut image = [0; 3];
                for (d, w) in words[n..].iter().enumerate() {
                    image[d] = w
                        .parse()
                        .map_err(|_| at(l, &format!("image flag `{w}` is not an integer")))?;
                }
                image
            }
            false => [0; 3],
        };
        Ok(Atom {
            id: integer(l, 0, "atom id")?,
            molecule: molecular
                .then(|| integer(l, 1, "molecule id"))
                .transpose()?,
            kind: type_in(l, kind_column, self.atom_types, "atom")?,
            charge: (style == AtomStyle::Full)
                .then(|| floats(l, 3..4).map(|q| q[0]))
                .transpose()?,
            position: [xyz[0], xyz[1], xyz[2]],
            image,
            velocity: None,
        })
    }

    /// A bond or angle line: its id, type and `K` distinct atoms of `ids` (the error names the
    /// line).
    fn topology<const K: usize>(
        &self,
        l: &Line,
        ids: &BTreeSet<u64>,
        types: u32,
        what: &str,
    ) -> Result<(u64, u32, [u64; K]), String> {
        let words = l.text.split_whitespace().count();
        if words != K + 2 {
            return Err(at(
                l,
                &format!("a {what} line is `id type` and {K} atom ids"),
            ));
        }
        let id = integer(l, 0, "id")?;
        let mut atoms = [0; K];
        for k in 0..K {
            let a = integer(l, k + 2, "atom id")?;
            if !ids.contains(&a) {
                let why = format!("{what} {id} names atom {a}, which is not in Atoms");
                return Err(at(l, &why));
            }
            if atoms[..k].contains(&a) {
                return Err(at(l, &format!("{what} {id} names atom {a} twice")));
            }
            atoms[k] = a;
        }
        Ok((id, type_in(l, 1, types, what)?, atoms))
    }

    /// Checks across sections: the atoms, bonds and angles the header counts, every atom with
    /// a velocity once any has one.
    fn check(&self, counts: &Header) -> Result<(), String> {
        for (count, read, name) in [
            (counts.atoms, self.atoms.len(), "Atoms"),
            (counts.bonds, self.bonds.len(), "Bonds"),
            (counts.angles, self.angles.len(), "Angles"),
        ] {
            if count > 0 && read == 0 {
                return Err(format!(
                    "the header has {count} {} and no `{name}` section",
                    name.to_lowercase()
                ));
            }
        }
        if self.atoms.iter().any(|a| a.velocity.is_some())
            && self.atoms.iter().any(|a| a.velocity.is_none())
        {
            return Err("section `Velocities`: gives some atoms no velocity".into());
        }
        Ok(())
    }
}

/// The header's counts.
#[derive(Default)]
struct Header {
    atoms: usize,
    bonds: usize,
    angles: usize,
}

impl Header {
    /// Read one header line into the counts and `file`.
    fn read(&mut self, l: &Line, file: &mut DataFile) -> Result<(), String> {
        let words: Vec<&str> = l.text.split_whitespace().collect();
        let count = || integer(l, 0, "count");
        match words[..] {
            [_, "atoms"] => self.atoms = count()? as usize,
            [_, "bonds"] => self.bonds = count()? as usize,
            [_, "angles"] => self.angles = count()? as usize,
            [_, "atom", "types"] => file.atom_types = count()? as u32,
            [_, "bond", "types"] => file.bond_types = count()? as u32,
            [_, "angle", "types"] => file.angle_types = count()? as u32,
            [_, "dihedrals" | "impropers"] | [_, "dihedral" | "improper", "types"] => {
                if count()? > 0 {
                    return Err(at(l, "dihedrals and impropers are not read here"));
                }
            }
            [_, _, lo, hi] if lo.ends_with("lo") && hi.ends_with("hi") && lo[..1] == hi[..1] => {
                let d = ["x", "y", "z"]
                    .iter()
                    .position(|a| lo.strip_suffix("lo") == Some(a))
                    .ok_or_else(|| at(l, "unknown box bounds"))?;
                let b = floats(l, 0..2)?; // finite
                if b[0] >= b[1] {
                    return Err(at(l, "a box bound needs lo < hi"));
                }
                file.bounds[d] = [b[0], b[1]];
            }
            [_, _, _, "xy", "xz", "yz"] => return Err(at(l, "triclinic boxes are not read here")),
            _ => {
                return Err(at(
                    l,
                    "is no header line read here (counts, types, box bounds)",
                ))
            }
        }
        Ok(())
    }

    /// Lines section `name` must have.
    fn rows(&self, name: &str, file: &DataFile) -> usize {
        match name {
            "Atoms" | "Velocities" => self.atoms,
            "Bonds" => self.bonds,
            "Angles" => self.angles,
            "Atom Type Labels" | "Masses" | "Pair Coeffs" => file.atom_types as usize,
            "PairIJ Coeffs" => {
                let t = file.atom_types as usize;
                t * (t + 1) / 2
            }
            "Bond Coeffs" => file.bond_types as usize,
            _ => file.angle_types as usize,
        }
    }
}

/// The title (the first line) and the other non-blank lines of `text`, numbered from 1,
/// comments split off.
fn lines(text: &str) -> (&str, Peekable<impl Iterator<Item = Line<'_>>>) {
    let mut all = text.lines().enumerate().map(|(k, l)| {
        let (text, comment) = l.split_once('#').unwrap_or((l, ""));
        Line {
            number: k + 1,
            text: text.trim(),
            comment: comment.trim(),
            section: "",
        }
    });
    let title = all.next().map_or("", |l| l.text);
    (title, all.filter(|l| !l.text.is_empty()).peekable())
}

/// The name of the section `head` opens, if it is one read here.
fn section_name<'a>(head: &Line<'a>) -> Result<&'a str, String> {
    if SECTIONS.contains(&head.text) {
        Ok(head.text)
    } else {
        Err(format!(
            "line {}: section `{}` is not read here (known: {})",
            head.number,
            head.text,
            SECTIONS.join(", ")
        ))
    }
}

/// The error of a line of section `l.section` whose first word, not a number, made it look
/// like a section heading.
fn not_a_number(l: &Line) -> String {
    let first = l.text.split_whitespace().next().unwrap_or("");
    let why = format!(
        "`{first}` is not a number, and no section read here is named so (known: {})",
        SECTIONS.join(", ")
    );
    at(l, &why)
}

/// A section's heading: a line that begins with a letter (data lines begin with numbers).
fn is_section(text: &str) -> bool {
    text.starts_with(|c: char| c.is_ascii_alphabetic())
}

/// The error `what` of line `l`, naming its number and section and quoting it.
fn at(l: &Line, what: &str) -> String {
    let part = match l.section {
        "" => "the header".to_string(),
        name => format!("section `{name}`"),
    };
    format!("line {} ({part}): {what}: `{}`", l.number, l.text)
}

/// The numbers of `l` in the columns `range`.
fn floats(l: &Line, range: impl std::ops::RangeBounds<usize>) -> Result<Vec<f64>, String> {
    let words: Vec<&str> = l.text.split_whitespace().collect();
    let (lo, hi) = (
        match range.start_bound() {
            std::ops::Bound::Included(&s) => s,
            _ => 0,
        },
        match range.end_bound() {
            std::ops::Bound::Excluded(&e) => e,
            _ => words.len(),
        },
    );
    let cells = words.get(lo..hi).ok_or_else(|| at(l, "too few columns"))?;
    cells
        .iter()
        .map(|w| match w.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => Err(at(l, &format!("`{w}` is not a finite number"))),
        })
        .collect()
}

fn integer(l: &Line, column: usize, what: &str) -> Result<u64, String> {
    let w = l.text.split_whitespace().nth(column).unwrap_or("");
    w.parse()
        .map_err(|_| at(l, &format!("{what} `{w}` is not a whole number >= 0")))
}

/// The type in `column` of `l`, checked to be 1 to `types`.
fn type_in(l: &Line, column: usize, types: u32, what: &str) -> Result<u32, String> {
    let t = integer(l, column, &format!("{what} type"))?;
    if t == 0 || t > u64::from(types) {
        return Err(at(
            l,
            &format!("{what} type {t} is not in 1 to {types} (the header's {what} types)"),
        ));
    }
    Ok(t as u32)
}

fn joined(values: &[f64]) -> String {
    let words: Vec<String> = values.iter().map(f64::to_string).collect();
    words.join(" ")
}

#[cfg(test)]
mod tests;
