//! GSD files (file layer 2.1) with the HOOMD schema 1.4, written and read directly.
//!
//! Layout of a file this writer makes: the 256-byte header, the name list (every chunk name,
//! fixed when the file is created), the index (32-byte entries, sorted by frame and then by
//! name id, ended by the first entry at location 0), and the data chunks appended after it.
//!
//! Commit: a frame's chunks are appended first; then its index entries are written in one
//! write into the zeroed tail of the index, which is what makes the frame exist for a reader.
//! When the index is full, a larger copy holding the new entries is appended and the header is
//! rewritten to point at it (one 256-byte write). A kill at any point thus leaves a file whose
//! index names only frames whose chunks are complete.
//!
//! Type names, type ids and masses are written in frame 0 and again only in a frame where they
//! change: the HOOMD schema reads a chunk missing from a frame from frame 0.

use super::{Bonds, Frame, TrajectoryError};
use std::fs::File;
use std::os::unix::fs::FileExt;
use std::path::{Path, PathBuf};

const MAGIC: u64 = 0x65DF_65DF_65DF_65DF;
const HEADER_BYTES: u64 = 256;
const ENTRY_BYTES: u64 = 32;
/// The name list is allocated in segments of this many bytes.
const NAME_SEGMENT: usize = 64;
/// Index entries allocated when the file is created; the index doubles when full.
const INITIAL_ENTRIES: u64 = 256;

/// `major.minor` packed as the GSD header stores versions.
const fn version(major: u32, minor: u32) -> u32 {
    (major << 16) | minor
}

/// GSD chunk element types (the file layer's type ids).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
enum Kind {
    U8 = 1,
    U32 = 3,
    U64 = 4,
    I8 = 5,
    I32 = 7,
    F32 = 9,
    F64 = 10,
}

impl Kind {
    fn from_id(id: u8) -> Option<Kind> {
        [
            Kind::U8,
            Kind::U32,
            Kind::U64,
            Kind::I8,
            Kind::I32,
            Kind::F32,
            Kind::F64,
        ]
        .into_iter()
        .find(|k| *k as u8 == id)
    }

    fn size(self) -> u64 {
        match self {
            Kind::U8 | Kind::I8 => 1,
            Kind::U32 | Kind::I32 | Kind::F32 => 4,
            Kind::U64 | Kind::F64 => 8,
        }
    }
}

/// The chunks of the HOOMD schema this writer fills, before the `log/` names.
const CONFIGURATION: [&str; 2] = ["configuration/box", "configuration/step"];
/// The particle chunks, after the `log/` names.
const PARTICLES: [&str; 7] = [
    "particles/N",
    "particles/image",
    "particles/mass",
    "particles/position",
    "particles/typeid",
    "particles/types",
    "particles/velocity",
];

/// The bond chunks, after the particles'.
const BONDS: [&str; 4] = ["bonds/N", "bonds/group", "bonds/typeid", "bonds/types"];

/// The `log/` scalars every frame carries: its time step and simulation time, which the HOOMD
/// schema leaves to the application (`configuration/step` is the step alone).
const TIME_LOGS: [&str; 2] = ["dt", "time"];

/// One index entry: where a chunk of a frame is and what it holds.
#[derive(Clone, Copy, Debug)]
struct Entry {
    frame: u64,
    n: u64,
    location: u64,
    m: u32,
    id: u16,
    kind: u8,
}

impl Entry {
    fn to_bytes(self) -> [u8; ENTRY_BYTES as usize] {
        let mut b = [0u8; ENTRY_BYTES as usize];
        b[0..8].copy_from_slice(&self.frame.to_le_bytes());
        b[8..16].copy_from_slice(&self.n.to_le_bytes());
        b[16..24].copy_from_slice(&self.location.to_le_bytes());
        b[24..28].copy_from_slice(&self.m.to_le_bytes());
        b[28..30].copy_from_slice(&self.id.to_le_bytes());
        b[30] = self.kind;
        // b[31]: flags, 0.
        b
    }

    fn from_bytes(b: &[u8]) -> Entry {
        let u64_at = |i: usize| u64::from_le_bytes(b[i..i + 8].try_into().unwrap_or_default());
        Entry {
            frame: u64_at(0),
            n: u64_at(8),
            location: u64_at(16),
            m: u32::from_le_bytes(b[24..28].try_into().unwrap_or_default()),
            id: u16::from_le_bytes([b[28], b[29]]),
            kind: b[30],
        }
    }

    fn bytes(&self) -> u64 {
        self.n * u64::from(self.m) * Kind::from_id(self.kind).map_or(0, Kind::size)
    }
}

/// The fixed part of the file: where the index and the name list are.
struct Header {
    index_location: u64,
    index_entries: u64,
    namelist_location: u64,
    namelist_segments: u64,
}

impl Header {
    fn to_bytes(&self) -> [u8; HEADER_BYTES as usize] {
        let mut b = [0u8; HEADER_BYTES as usize];
        let words = [
            MAGIC,
            self.index_location,
            self.index_entries,
            self.namelist_location,
            self.namelist_segments,
        ];
        for (i, w) in words.iter().enumerate() {
            b[8 * i..8 * i + 8].copy_from_slice(&w.to_le_bytes());
        }
        b[40..44].copy_from_slice(&version(1, 4).to_le_bytes());
        b[44..48].copy_from_slice(&version(2, 1).to_le_bytes());
        let application = concat!("dpd ", env!("CARGO_PKG_VERSION"));
        b[48..48 + application.len()].copy_from_slice(application.as_bytes());
        b[112..117].copy_from_slice(b"hoomd");
        b
    }
}

/// A chunk of the frame being written: its name id, element type, shape and bytes.
struct Chunk {
    id: u16,
    kind: Kind,
    n: u64,
    m: u32,
    data: Vec<u8>,
}

/// Appends frames to a GSD file; see the module documentation for the commit order.
pub struct GsdWriter {
    file: File,
    path: PathBuf,
    names: Vec<String>,
    header: Header,
    /// Entries committed so far, in file order.
    entries: Vec<Entry>,
    /// End of the file: where the next chunk goes.
    end: u64,
    frame: u64,
    /// Frame 0's type names, type ids and masses; later frames write them only when they differ.
    first: Option<Frame>,
}

impl GsdWriter {
    /// Create (or truncate) `path`; `log_names` are the `log/<name>` scalars frames may carry.
    pub fn create(path: &Path, log_names: &[&str]) -> Result<GsdWriter, TrajectoryError> {
        let mut names: Vec<String> = CONFIGURATION.iter().map(|s| s.to_string()).collect();
        let mut logs: Vec<String> = TIME_LOGS
            .iter()
            .chain(log_names)
            .map(|s| format!("log/{s}"))
            .collect();
        logs.sort();
        logs.dedup();
        names.extend(logs);
        names.extend(PARTICLES.iter().chain(&BONDS).map(|s| s.to_string()));
        let mut namelist: Vec<u8> = names
            .iter()
            .flat_map(|s| [s.as_bytes(), b"\0"].concat())
            .collect();
        // At least one zero byte after the last name ends the list.
        namelist.resize((namelist.len() / NAME_SEGMENT + 1) * NAME_SEGMENT, 0);
        let namelist_location = HEADER_BYTES;
        let index_location = namelist_location + namelist.len() as u64;
        let header = Header {
            index_location,
            index_entries: INITIAL_ENTRIES,
            namelist_location,
            namelist_segments: (namelist.len() / NAME_SEGMENT) as u64,
        };
        let end = index_location + INITIAL_ENTRIES * ENTRY_BYTES;
        let mut start = header.to_bytes().to_vec();
        start.extend(namelist);
        start.resize(end as usize, 0);
        let file = File::create(path).map_err(TrajectoryError::io(path))?;
        file.write_all_at(&start, 0)
            .map_err(TrajectoryError::io(path))?;
        Ok(GsdWriter {
            file,
            path: path.to_path_buf(),
            names,
            header,
            entries: Vec::new(),
            end,
            frame: 0,
            first: None,
        })
    }

    fn id(&self, name: &str) -> Result<u16, TrajectoryError> {
        self.names
            .iter()
            .position(|n| n == name)
            .map(|i| i as u16)
            .ok_or_else(|| {
                TrajectoryError::Frame(format!(
                    "{name} was not among the log names given when {} was created",
                    self.path.display()
                ))
            })
    }

    /// The chunks of `f`, sorted by name id.
    fn chunks(&self, f: &Frame) -> Result<Vec<Chunk>, TrajectoryError> {
        let n = f.len() as u64;
        let mut out = Vec::new();
        let first = self.first.as_ref();
        let mut add = |name: &str,
                       kind: Kind,
                       n: u64,
                       m: u32,
                       data: Vec<u8>|
         -> Result<(), TrajectoryError> {
            out.push(Chunk {
                id: self.id(name)?,
                kind,
                n,
                m,
                data,
            });
            Ok(())
        };
        // HOOMD's box: L_x, L_y, L_z and the tilts xy, xz, yz (zero: orthorhombic).
        let [lx, ly, lz] = f.box_lengths;
        add(
            "configuration/box",
            Kind::F32,
            6,
            1,
            f32s([lx, ly, lz, 0.0, 0.0, 0.0].iter().copied()),
        )?;
        add(
            "configuration/step",
            Kind::U64,
            1,
            1,
            f.step.to_le_bytes().to_vec(),
        )?;
        let times = [("dt", f.dt), ("time", f.time)];
        let logs = times
            .into_iter()
            .chain(f.log.iter().map(|(n, v)| (n.as_str(), *v)));
        for (name, value) in logs {
            add(
                &format!("log/{name}"),
                Kind::F64,
                1,
                1,
                value.to_le_bytes().to_vec(),
            )?;
        }
        add(
            "particles/N",
            Kind::U32,
            1,
            1,
            (n as u32).to_le_bytes().to_vec(),
        )?;
        // HOOMD's positions are in [-L/2, L/2).
        let centred = f
            .positions
            .iter()
            .flat_map(|q| (0..3).map(move |k| q[k] - 0.5 * f.box_lengths[k]));
        add("particles/position", Kind::F32, n, 3, f32s(centred))?;
        if let Some(v) = &f.velocities {
            add(
                "particles/velocity",
                Kind::F32,
                n,
                3,
                f32s(v.iter().flatten().copied()),
            )?;
        }
        if let Some(im) = &f.images {
            let bytes = im.iter().flatten().flat_map(|i| i.to_le_bytes()).collect();
            add("particles/image", Kind::I32, n, 3, bytes)?;
        }
        if first.is_none_or(|g| g.types != f.types) {
            let (width, bytes) = names_bytes(&f.types);
            add(
                "particles/types",
                Kind::I8,
                f.types.len() as u64,
                width,
                bytes,
            )?;
        }
        if first.is_none_or(|g| g.typeid != f.typeid) {
            let bytes = f.typeid.iter().flat_map(|t| t.to_le_bytes()).collect();
            add("particles/typeid", Kind::U32, n, 1, bytes)?;
        }
        if let Some(m) = f
            .masses
            .as_ref()
            .filter(|m| first.is_none_or(|g| g.masses.as_ref() != Some(m)))
        {
            add("particles/mass", Kind::F32, n, 1, f32s(m.iter().copied()))?;
        }
        if let Some(b) = f
            .bonds
            .as_ref()
            .filter(|b| first.is_none_or(|g| g.bonds.as_ref() != Some(b)))
        {
            let count = b.group.len() as u64;
            add(
                "bonds/N",
                Kind::U32,
                1,
                1,
                (count as u32).to_le_bytes().to_vec(),
            )?;
            let (width, bytes) = names_bytes(&b.types);
            add("bonds/types", Kind::I8, b.types.len() as u64, width, bytes)?;
            let typeid = b.typeid.iter().flat_map(|t| t.to_le_bytes()).collect();
            add("bonds/typeid", Kind::U32, count, 1, typeid)?;
            let group = b
                .group
                .iter()
                .flatten()
                .flat_map(|i| i.to_le_bytes())
                .collect();
            add("bonds/group", Kind::U32, count, 2, group)?;
        }
        out.sort_by_key(|c| c.id);
        Ok(out)
    }

    /// Append `f` and commit it (see the module documentation).
    pub fn append(&mut self, f: &Frame) -> Result<(), TrajectoryError> {
        let chunks = self.chunks(f)?;
        let mut data = Vec::new();
        let mut new = Vec::with_capacity(chunks.len());
        for c in chunks {
            new.push(Entry {
                frame: self.frame,
                n: c.n,
                location: self.end + data.len() as u64,
                m: c.m,
                id: c.id,
                kind: c.kind as u8,
            });
            data.extend(c.data);
        }
        let io = TrajectoryError::io;
        self.file
            .write_all_at(&data, self.end)
            .map_err(io(&self.path))?;
        self.end += data.len() as u64;
        let used = self.entries.len() as u64;
        self.entries.extend(&new);
        let total = self.entries.len() as u64;
        if total < self.header.index_entries {
            let bytes: Vec<u8> = new.iter().flat_map(|e| e.to_bytes()).collect();
            let at = self.header.index_location + used * ENTRY_BYTES;
            self.file.write_all_at(&bytes, at).map_err(io(&self.path))?;
        } else {
            // A larger index (with a zero entry after the last) at the end, then the header.
            let capacity = (2 * self.header.index_entries).max(total + 1);
            let mut bytes: Vec<u8> = self.entries.iter().flat_map(|e| e.to_bytes()).collect();
            bytes.resize((capacity * ENTRY_BYTES) as usize, 0);
            self.file
                .write_all_at(&bytes, self.end)
                .map_err(io(&self.path))?;
            self.header.index_location = self.end;
            self.header.index_entries = capacity;
            self.end += bytes.len() as u64;
            self.file
                .write_all_at(&self.header.to_bytes(), 0)
                .map_err(io(&self.path))?;
        }
        if self.first.is_none() {
            self.first = Some(Frame {
                types: f.types.clone(),
                typeid: f.typeid.clone(),
                masses: f.masses.clone(),
                bonds: f.bonds.clone(),
                ..Frame::default()
            });
        }
        self.frame += 1;
        Ok(())
    }
}

/// `names` as GSD stores type names: each padded with zeros to the longest plus one; the
/// width and the bytes.
fn names_bytes(names: &[String]) -> (u32, Vec<u8>) {
    let width = names.iter().map(|t| t.len()).max().unwrap_or(0) + 1;
    let bytes = names.iter().flat_map(|t| {
        let mut b = t.as_bytes().to_vec();
        b.resize(width, 0);
        b
    });
    (width as u32, bytes.collect())
}

/// Names stored `width` bytes each, zero-padded (see [`names_bytes`]).
fn names_of(width: u32, bytes: &[u8]) -> Vec<String> {
    let each = bytes.chunks_exact(width.max(1) as usize);
    let name = |t: &[u8]| t.split(|&c| c == 0).next().unwrap_or_default().to_vec();
    each.map(|t| String::from_utf8_lossy(&name(t)).into_owned())
        .collect()
}

/// Little-endian u32s of `bytes`.
fn u32s(bytes: &[u8]) -> Vec<u32> {
    let each = bytes.chunks_exact(4);
    each.map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}

/// Little-endian f32 bytes of `values` (the schema stores positions, velocities, masses and
/// the box in single precision).
fn f32s(values: impl Iterator<Item = f64>) -> Vec<u8> {
    values.flat_map(|x| (x as f32).to_le_bytes()).collect()
}

/// A GSD file opened for reading frames of the HOOMD schema.
pub struct GsdReader {
    file: File,
    path: PathBuf,
    names: Vec<String>,
    entries: Vec<Entry>,
    frames: u64,
}

impl GsdReader {
    pub fn open(path: &Path) -> Result<GsdReader, TrajectoryError> {
        let file = File::open(path).map_err(TrajectoryError::io(path))?;
        let bad = |message: String| TrajectoryError::Format {
            path: path.to_path_buf(),
            message,
        };
        let size = file.metadata().map_err(TrajectoryError::io(path))?.len();
        let mut h = [0u8; HEADER_BYTES as usize];
        if size < HEADER_BYTES || file.read_exact_at(&mut h, 0).is_err() {
            return Err(bad(format!("{size} bytes: too short for a GSD header")));
        }
        let word =
            |i: usize| u64::from_le_bytes(h[8 * i..8 * i + 8].try_into().unwrap_or_default());
        if word(0) != MAGIC {
            return Err(bad("not a GSD file (no GSD magic number)".into()));
        }
        let gsd_version = u32::from_le_bytes(h[44..48].try_into().unwrap_or_default());
        if !(version(2, 0)..version(3, 0)).contains(&gsd_version) {
            return Err(bad(format!(
                "GSD file layer version {}.{}; readable: 2.x",
                gsd_version >> 16,
                gsd_version & 0xffff
            )));
        }
        if &h[112..118] != b"hoomd\0" {
            return Err(bad(
                "not a HOOMD-schema GSD file (schema name is not \"hoomd\")".into(),
            ));
        }
        let (index_location, index_entries) = (word(1), word(2));
        let (namelist_location, namelist_segments) = (word(3), word(4));
        let read = |at: u64, len: u64, what: &str| -> Result<Vec<u8>, TrajectoryError> {
            if at.checked_add(len).is_none_or(|e| e > size) {
                return Err(bad(format!(
                    "the {what} ({len} bytes at {at}) ends past the file's {size} bytes"
                )));
            }
            let mut b = vec![0u8; len as usize];
            file.read_exact_at(&mut b, at)
                .map_err(TrajectoryError::io(path))?;
            Ok(b)
        };
        let namelist = read(
            namelist_location,
            namelist_segments * NAME_SEGMENT as u64,
            "name list",
        )?;
        let names = namelist
            .split(|&b| b == 0)
            .take_while(|s| !s.is_empty())
            .map(|s| String::from_utf8_lossy(s).into_owned())
            .collect();
        let index = read(index_location, index_entries * ENTRY_BYTES, "index")?;
        let entries: Vec<Entry> = index
            .chunks_exact(ENTRY_BYTES as usize)
            .map(Entry::from_bytes)
            .take_while(|e| e.location != 0)
            .collect();
        for e in &entries {
            if Kind::from_id(e.kind).is_none() || e.location.saturating_add(e.bytes()) > size {
                return Err(bad(format!(
                    "index entry of frame {} is invalid or ends past the file",
                    e.frame
                )));
            }
        }
        let frames = entries.last().map_or(0, |e| e.frame + 1);
        Ok(GsdReader {
            file,
            path: path.to_path_buf(),
            names,
            entries,
            frames,
        })
    }

    /// Number of frames.
    pub fn frames(&self) -> u64 {
        self.frames
    }

    /// The chunk `name` of `frame`, else of frame 0 (the schema's rule), as element type and
    /// bytes with its shape.
    fn chunk(&self, frame: u64, name: &str) -> Result<Option<(Entry, Vec<u8>)>, TrajectoryError> {
        let Some(id) = self.names.iter().position(|n| n == name) else {
            return Ok(None);
        };
        let find = |f: u64| {
            self.entries
                .iter()
                .find(|e| e.frame == f && usize::from(e.id) == id)
        };
        let Some(e) = find(frame).or_else(|| find(0)).copied() else {
            return Ok(None);
        };
        let mut b = vec![0u8; e.bytes() as usize];
        self.file
            .read_exact_at(&mut b, e.location)
            .map_err(TrajectoryError::io(&self.path))?;
        Ok(Some((e, b)))
    }

    /// The chunk `name` as floating-point numbers, `m` per particle, checking its shape.
    fn floats(
        &self,
        frame: u64,
        name: &str,
        n: u64,
        m: u32,
    ) -> Result<Option<Vec<f64>>, TrajectoryError> {
        let Some((e, b)) = self.chunk(frame, name)? else {
            return Ok(None);
        };
        if e.n != n || e.m != m {
            return Err(self.bad(
                frame,
                format!("{name} is {} x {}, expected {n} x {m}", e.n, e.m),
            ));
        }
        match Kind::from_id(e.kind) {
            Some(Kind::F32) => Ok(Some(
                b.chunks_exact(4)
                    .map(|c| f64::from(f32::from_le_bytes([c[0], c[1], c[2], c[3]])))
                    .collect(),
            )),
            Some(Kind::F64) => Ok(Some(
                b.chunks_exact(8)
                    .map(|c| f64::from_le_bytes(c.try_into().unwrap_or_default()))
                    .collect(),
            )),
            _ => Err(self.bad(
                frame,
                format!("{name} is not floating point (GSD type {})", e.kind),
            )),
        }
    }

    /// The bonds of `frame` (`None` without `bonds/N` or with none).
    fn bonds(&self, frame: u64) -> Result<Option<Bonds>, TrajectoryError> {
        let count = match self.chunk(frame, "bonds/N")? {
            Some((e, b)) if e.kind == Kind::U32 as u8 && b.len() == 4 => u64::from(u32s(&b)[0]),
            Some(_) => return Err(self.bad(frame, "bonds/N is not one uint32".into())),
            None => 0,
        };
        if count == 0 {
            return Ok(None);
        }
        let u32_chunk = |name: &str, m: u32| match self.chunk(frame, name)? {
            Some((e, b)) if e.kind == Kind::U32 as u8 && e.n == count && e.m == m => Ok(u32s(&b)),
            _ => Err(self.bad(frame, format!("{name} is not {count} x {m} uint32"))),
        };
        let types = match self.chunk(frame, "bonds/types")? {
            Some((e, b)) if e.m > 0 => names_of(e.m, &b),
            _ => return Err(self.bad(frame, "has bonds and no bonds/types".into())),
        };
        let group = u32_chunk("bonds/group", 2)?;
        Ok(Some(Bonds {
            types,
            typeid: u32_chunk("bonds/typeid", 1)?,
            group: group.chunks_exact(2).map(|g| [g[0], g[1]]).collect(),
        }))
    }

    fn bad(&self, frame: u64, message: String) -> TrajectoryError {
        TrajectoryError::Format {
            path: self.path.clone(),
            message: format!("frame {frame}: {message}"),
        }
    }

    /// Frame `frame` (counted from 0) with positions wrapped into `[0, L)`. Chunks missing from
    /// the frame come from frame 0; missing there too, velocities are zero, type ids 0 (type
    /// "A"), masses 1, images `None`, `dt` 0 (unknown: a file of another program) and `time`
    /// step x dt.
    pub fn frame(&self, frame: u64) -> Result<Frame, TrajectoryError> {
        if frame >= self.frames {
            return Err(TrajectoryError::Format {
                path: self.path.clone(),
                message: format!(
                    "frame {frame} is out of range: the file has {} frames (0 to {})",
                    self.frames,
                    self.frames.saturating_sub(1)
                ),
            });
        }
        let n = match self.chunk(frame, "particles/N")? {
            Some((e, b)) if e.kind == Kind::U32 as u8 && b.len() == 4 => {
                u64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            }
            Some(_) => return Err(self.bad(frame, "particles/N is not one uint32".into())),
            None => 0,
        };
        let bx = self
            .floats(frame, "configuration/box", 6, 1)?
            .ok_or_else(|| self.bad(frame, "has no configuration/box".into()))?;
        if bx[3..].iter().any(|&t| t != 0.0) {
            return Err(self.bad(
                frame,
                format!(
                    "the box is tilted (xy, xz, yz = {:?}); only orthorhombic boxes are read",
                    &bx[3..]
                ),
            ));
        }
        let box_lengths = [bx[0], bx[1], bx[2]];
        let triples = |v: Vec<f64>| {
            v.chunks_exact(3)
                .map(|c| [c[0], c[1], c[2]])
                .collect::<Vec<_>>()
        };
        let positions = self
            .floats(frame, "particles/position", n, 3)?
            .map(triples)
            .unwrap_or_else(|| vec![[0.0; 3]; n as usize])
            .into_iter()
            .map(|q| {
                std::array::from_fn(|k| (q[k] + 0.5 * box_lengths[k]).rem_euclid(box_lengths[k]))
            })
            .collect();
        let velocities = Some(
            self.floats(frame, "particles/velocity", n, 3)?
                .map(triples)
                .unwrap_or_else(|| vec![[0.0; 3]; n as usize]),
        );
        let masses = Some(
            self.floats(frame, "particles/mass", n, 1)?
                .unwrap_or_else(|| vec![1.0; n as usize]),
        );
        let typeid = match self.chunk(frame, "particles/typeid")? {
            Some((e, b)) if e.kind == Kind::U32 as u8 && e.n == n => u32s(&b),
            Some(_) => return Err(self.bad(frame, format!("particles/typeid is not {n} uint32"))),
            None => vec![0; n as usize],
        };
        let types = match self.chunk(frame, "particles/types")? {
            Some((e, b)) if e.m > 0 => names_of(e.m, &b),
            _ => vec!["A".to_string()],
        };
        let step = match self.chunk(frame, "configuration/step")? {
            Some((_, b)) if b.len() == 8 => u64::from_le_bytes(b.try_into().unwrap_or_default()),
            _ => 0,
        };
        let images = match self.chunk(frame, "particles/image")? {
            Some((e, b)) if e.kind == Kind::I32 as u8 && e.n == n && e.m == 3 => Some(
                b.chunks_exact(12)
                    .map(|c| {
                        std::array::from_fn(|k| {
                            i32::from_le_bytes([c[4 * k], c[4 * k + 1], c[4 * k + 2], c[4 * k + 3]])
                        })
                    })
                    .collect(),
            ),
            Some(_) => return Err(self.bad(frame, format!("particles/image is not {n} x 3 int32"))),
            None => None,
        };
        let scalar = |name: &str| -> Result<Option<f64>, TrajectoryError> {
            Ok(self.floats(frame, name, 1, 1)?.map(|v| v[0]))
        };
        let dt = scalar("log/dt")?.unwrap_or(0.0);
        let time = scalar("log/time")?.unwrap_or(step as f64 * dt);
        let out = Frame {
            step,
            time,
            dt,
            box_lengths,
            positions,
            velocities,
            images,
            typeid,
            types,
            masses,
            log: Vec::new(),
            bonds: self.bonds(frame)?,
        };
        out.check().map_err(|e| self.bad(frame, e.to_string()))?;
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(step: u64) -> Frame {
        let s = step as f64;
        Frame {
            step,
            time: 10.0 + 0.5 * s,
            dt: 0.5,
            box_lengths: [4.0, 5.0, 6.0],
            positions: vec![[0.25 + 0.01 * s, 4.75, 3.0], [3.5, 0.0, 5.9]],
            velocities: Some(vec![[1.0, -2.0, s], [0.5, 0.25, -0.125]]),
            images: Some(vec![[1, 0, -1], [0, 0, 0]]),
            typeid: vec![0, 1],
            types: vec!["A".into(), "Wall".into()],
            masses: Some(vec![1.0, 2.0]),
            log: vec![("kinetic_temperature".into(), 1.0 + s)],
            bonds: Some(Bonds {
                types: vec!["backbone".into()],
                typeid: vec![0],
                group: vec![[1, 0]],
            }),
        }
    }

    fn close(a: &[[f64; 3]], b: &[[f64; 3]]) -> bool {
        // f32 storage: a relative 1e-6 of the box edge.
        a.iter()
            .flatten()
            .zip(b.iter().flatten())
            .all(|(x, y)| (x - y).abs() < 1e-5)
    }

    #[test]
    fn frames_read_back_past_a_growth_of_the_index() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.gsd");
        let mut w = GsdWriter::create(&path, &["kinetic_temperature"]).unwrap();
        // 12 chunks in frame 0 and 6 after: 100 frames pass the 256 initial entries twice.
        for step in 0..100 {
            w.append(&frame(step)).unwrap();
        }
        let r = GsdReader::open(&path).unwrap();
        assert_eq!(r.frames(), 100);
        for step in [0, 31, 99] {
            let (got, want) = (r.frame(step).unwrap(), frame(step));
            assert_eq!((got.step, got.time, got.dt), (step, want.time, want.dt));
            assert_eq!(got.box_lengths, want.box_lengths);
            assert_eq!(got.images, want.images);
            assert!(
                close(&got.positions, &want.positions),
                "{:?}",
                got.positions
            );
            assert!(close(
                got.velocities.as_ref().unwrap(),
                want.velocities.as_ref().unwrap()
            ));
            // Types, masses and bonds are in frame 0 only and read from there.
            assert_eq!(
                (got.typeid, got.types, got.masses, got.bonds),
                (want.typeid, want.types, want.masses, want.bonds)
            );
        }
        let err = r.frame(100).err().unwrap().to_string();
        assert!(
            err.contains("frame 100 is out of range: the file has 100 frames"),
            "{err}"
        );
    }

    #[test]
    fn bonds_change_between_frames_and_bad_ones_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.gsd");
        let mut w = GsdWriter::create(&path, &["kinetic_temperature"]).unwrap();
        let none = Frame {
            bonds: None,
            ..frame(1)
        };
        w.append(&none).unwrap();
        w.append(&frame(2)).unwrap();
        let r = GsdReader::open(&path).unwrap();
        assert_eq!(
            (r.frame(0).unwrap().bonds, r.frame(1).unwrap().bonds),
            (None, frame(2).bonds)
        );
        let mut writer = crate::Writer::create(&path, &["kinetic_temperature"]).unwrap();
        for (typeid, group, message) in [
            (1, [0, 1], "bond 0: typeid 1 names no bond type"),
            (0, [1, 1], "bond 0 joins particles 1 and 1"),
            (0, [0, 2], "bond 0 joins particles 0 and 2"),
        ] {
            let mut f = frame(0);
            f.bonds = Some(Bonds {
                types: vec!["b".into()],
                typeid: vec![typeid],
                group: vec![group],
            });
            let e = writer.append(&f).unwrap_err().to_string();
            assert!(e.contains(message), "{e}");
        }
    }

    #[test]
    fn chunks_without_their_index_entries_are_not_a_frame() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.gsd");
        let mut w = GsdWriter::create(&path, &[]).unwrap();
        w.append(&Frame {
            log: vec![],
            ..frame(0)
        })
        .unwrap();
        w.append(&Frame {
            log: vec![],
            ..frame(1)
        })
        .unwrap();
        // What a kill after the data and before the commit leaves: a frame's bytes at the end.
        let orphan = vec![7u8; 200];
        w.file.write_all_at(&orphan, w.end).unwrap();
        let r = GsdReader::open(&path).unwrap();
        assert_eq!(r.frames(), 2);
        assert_eq!(r.frame(1).unwrap().step, 1);
    }

    #[test]
    fn a_log_name_not_reserved_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        let mut w = GsdWriter::create(&dir.path().join("t.gsd"), &[]).unwrap();
        let err = w.append(&frame(0)).err().unwrap().to_string();
        assert!(
            err.contains("log/kinetic_temperature was not among the log names"),
            "{err}"
        );
    }

    #[test]
    fn time_and_dt_are_not_log_names_of_their_own() {
        let dir = tempfile::tempdir().unwrap();
        let mut w = crate::Writer::create(&dir.path().join("t.gsd"), &["time"]).unwrap();
        let f = Frame {
            log: vec![("time".into(), 1.0)],
            ..frame(0)
        };
        let err = w.append(&f).err().unwrap();
        assert!(err.to_string().contains("\"time\" is reserved"), "{err}");
    }

    #[test]
    fn other_files_are_refused_by_name() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.gsd");
        std::fs::write(&path, vec![0u8; 300]).unwrap();
        let err = GsdReader::open(&path).err().unwrap().to_string();
        assert!(err.contains("not a GSD file"), "{err}");
        let err = GsdReader::open(&dir.path().join("none.gsd"))
            .err()
            .unwrap()
            .to_string();
        assert!(err.contains("none.gsd"), "{err}");
    }
}
