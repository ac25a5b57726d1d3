//! The LAMMPS plugin source tree of `dpd export lammps` (docs/lammps.md): the fixed runtime of
//! `lammps/plugin/` (embedded at compile time, its `CMakeLists.txt` included), a generated
//! `schemes.cpp` with the stage table of every exported scheme (dpd-ir's merged [`Program`]
//! stages, the ones `dpd check` analyses, repetitions written out, with adjacent kicks of the
//! two force groups by one coefficient joined into one kick: [`joined_kicks`]), and the `dpd-lammps` kernels as a prebuilt static
//! library, `kernels/libdpd_lammps.a`, so that the tree builds with CMake, a C++17 compiler and
//! LAMMPS alone.

use dpd::lang::{compile_with, Options};
use dpd::schemes::registry::lookup;
use dpd::{Flow, ForceGroup, Program, SweepOrder};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The fixed runtime: file name and contents.
const RUNTIME: [(&str, &str); 12] = [
    (
        "compute_temp_split.h",
        include_str!("../../../lammps/plugin/compute_temp_split.h"),
    ),
    (
        "compute_temp_split.cpp",
        include_str!("../../../lammps/plugin/compute_temp_split.cpp"),
    ),
    (
        "CMakeLists.txt",
        include_str!("../../../lammps/plugin/CMakeLists.txt"),
    ),
    (
        "fix_dpd_split.h",
        include_str!("../../../lammps/plugin/fix_dpd_split.h"),
    ),
    (
        "fix_dpd_split.cpp",
        include_str!("../../../lammps/plugin/fix_dpd_split.cpp"),
    ),
    (
        "pair_dpd_soft.h",
        include_str!("../../../lammps/plugin/pair_dpd_soft.h"),
    ),
    (
        "pair_dpd_soft.cpp",
        include_str!("../../../lammps/plugin/pair_dpd_soft.cpp"),
    ),
    (
        "plugin.cpp",
        include_str!("../../../lammps/plugin/plugin.cpp"),
    ),
    (
        "schemes.h",
        include_str!("../../../lammps/plugin/schemes.h"),
    ),
    (
        "dpd_lammps.h",
        include_str!("../../../lammps/plugin/dpd_lammps.h"),
    ),
    ("LICENSE", include_str!("../../../lammps/plugin/LICENSE")),
    (
        "README.md",
        include_str!("../../../lammps/plugin/README.md"),
    ),
];

/// Where the static library of the kernels goes in the tree.
pub const KERNELS: &str = "kernels/libdpd_lammps.a";

/// The workspace holding `lammps/kernels`, as compiled in (the exporter builds the kernels
/// there with cargo unless given a library).
pub fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map_or_else(|| PathBuf::from("."), Path::to_path_buf)
}

/// One scheme to export: the name as given, its identifier, and its program.
#[derive(Debug)]
pub struct Exported {
    pub name: String,
    pub ident: String,
    pub program: Program,
    pub consistent: bool,
}

/// The program of a registry name or scheme string (its kicks joined by [`joined_kicks`]), or
/// why it cannot be exported: unknown (the registry's message), hand-written, with an L, Oa, On or
/// Xi stage, Metropolis-adjusted (braces), or inconsistent without `allow_inconsistent`. Every other letter and force group runs in the
/// plugin (T only with `pair_style dpd/soft`, `B[bond]` only with bonded styles, which the fix
/// checks).
pub fn resolve(name: &str, allow_inconsistent: bool) -> Result<Exported, String> {
    let (label, program) = match lookup(name) {
        Ok(entry) => match entry.scheme().program() {
            Some(p) => (entry.name.to_string(), p.clone()),
            None => {
                return Err(format!(
                    "scheme '{name}' is hand-written on the core sub-flows ({}), not a \
                     splitting program of the scheme language, and the plugin runs only \
                     splitting programs",
                    entry.sequence()
                ))
            }
        },
        Err(unknown) => {
            let options = Options {
                allow_inconsistent: true,
            };
            match compile_with(name.trim(), &options) {
                Ok(p) => (name.trim().to_string(), p),
                Err(diagnostics) => {
                    let why: Vec<String> = diagnostics.iter().map(|d| d.to_string()).collect();
                    return Err(format!(
                        "{unknown} (`dpd schemes` lists them), and '{name}' is not a valid \
                         scheme string either: {}",
                        why.join("; ")
                    ));
                }
            }
        }
    };
    if program.stages.iter().any(|s| s.flow == Flow::L) {
        return Err(format!(
            "scheme '{name}' = {program} has L (Lowe-Andersen collisions), which the LAMMPS \
             plugin does not run: its kernels have no collision sweep (export a scheme of A, B, \
             O, Ob, T and F)"
        ));
    }
    if program
        .stages
        .iter()
        .any(|s| matches!(s.flow, Flow::Oa | Flow::On | Flow::Xi))
    {
        return Err(format!(
            "scheme '{name}' = {program} has Oa or On and Xi (the adaptive thermostats, PAdL and \
             PNHL), which the LAMMPS plugin does not run: its kernels have no adaptive friction xi (export a \
             scheme of A, B, O, Ob, T and F)"
        ));
    }
    if program.is_adjusted() {
        return Err(format!(
            "scheme '{name}' = {program} is Metropolis-adjusted ({{...}}), which the LAMMPS \
             plugin does not run: its accept/reject needs the energy difference of the whole \
             system over the Hamiltonian part, which the plugin's per-pair kernels do not have \
             (export a scheme of A, B, O, Ob, T and F)"
        ));
    }
    let program = joined_kicks(program);
    let consistent = program.analysis().consistent;
    if !consistent && !allow_inconsistent {
        return Err(format!(
            "scheme '{name}' = {program} is inconsistent (`dpd check` shows why); pass \
             --allow-inconsistent to export it anyway"
        ));
    }
    Ok(Exported {
        ident: identifier(&label),
        name: label,
        program,
        consistent,
    })
}

/// `program` with each pair of adjacent stages `B[pair](c) B[bond](c)` (either order, equal
/// coefficients) joined into one `B(c)`. Kicks of different groups commute (algorithms.md
/// section 4), so the step is the same map; in the plugin the joined kick applies LAMMPS's own
/// sum of all forces, where two kicks would need the forces split by group (a bonded
/// evaluation and a difference). So a multiple-time-stepping scheme with inner count 1, such as
/// `O(1/2) B[pair](1/2) (B[bond](1/2) A B[bond](1/2))^1 B[pair](1/2) O(1/2)`, runs as the flat
/// scheme (OBABO), bit for bit. The order analysis is unchanged (it reads the unmerged stages).
pub fn joined_kicks(mut program: Program) -> Program {
    let mut stages: Vec<dpd::Stage> = Vec::with_capacity(program.stages.len());
    for stage in program.stages {
        let complementary = |a: Option<ForceGroup>, b: Option<ForceGroup>| {
            matches!(
                (a, b),
                (Some(ForceGroup::Pair), Some(ForceGroup::Bond))
                    | (Some(ForceGroup::Bond), Some(ForceGroup::Pair))
            )
        };
        match stages.last_mut() {
            Some(top)
                if top.flow == Flow::B
                    && stage.flow == Flow::B
                    && complementary(top.group, stage.group)
                    && top.coeff == stage.coeff =>
            {
                top.group = None;
            }
            _ => stages.push(stage),
        }
    }
    program.stages = stages;
    program
}

/// A lowercase C identifier for a scheme name: letters and digits kept, every other run of
/// characters one `_`, a leading digit prefixed with `s`.
pub fn identifier(name: &str) -> String {
    let mut out = String::new();
    for c in name.trim().chars() {
        if c.is_ascii_alphanumeric() {
            out.push(c.to_ascii_lowercase());
        } else if !out.ends_with('_') {
            out.push('_');
        }
    }
    let out = out.trim_matches('_').to_string();
    match out.chars().next() {
        None => "scheme".to_string(),
        Some(c) if c.is_ascii_digit() => format!("s{out}"),
        Some(_) => out,
    }
}

/// A C string literal of `text`.
fn c_string(text: &str) -> String {
    let mut out = String::from("\"");
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if c.is_ascii() && !c.is_ascii_control() => out.push(c),
            c => {
                let mut bytes = [0; 4];
                for b in c.encode_utf8(&mut bytes).bytes() {
                    let _ = write!(out, "\\{b:03o}");
                }
            }
        }
    }
    out.push('"');
    out
}

/// The C++ enumerator of a flow (schemes.h, which has none for L, Oa, On, Xi and the braces:
/// [`resolve`] refuses them).
fn flow_name(flow: Flow) -> &'static str {
    match flow {
        Flow::A => "FLOW_A",
        Flow::B => "FLOW_B",
        Flow::O => "FLOW_O",
        Flow::Bbk => "FLOW_OB",
        Flow::T => "FLOW_T",
        Flow::F => "FLOW_F",
        Flow::L => "FLOW_L",
        Flow::Oa => "FLOW_OA",
        Flow::On => "FLOW_ON",
        Flow::Xi => "FLOW_XI",
        Flow::Propose => "FLOW_PROPOSE",
        Flow::Accept => "FLOW_ACCEPT",
    }
}

/// The C++ enumerator of a stage's force group (schemes.h): all forces, or one group.
fn group_name(group: Option<ForceGroup>) -> &'static str {
    match group {
        None => "GROUP_ALL",
        Some(ForceGroup::Pair) => "GROUP_PAIR",
        Some(ForceGroup::Bond) => "GROUP_BOND",
    }
}

/// `schemes.cpp`: the stage tables of `schemes`.
pub fn schemes_cpp(schemes: &[Exported]) -> String {
    let mut out = String::from(
        "/* Generated by `dpd export lammps`: the stage tables of the exported schemes.\n   \
         SPDX-License-Identifier: MIT */\n#include \"schemes.h\"\n\nnamespace DpdSplit {\n\n",
    );
    for s in schemes {
        let _ = writeln!(out, "// {} = {}", s.name, s.program);
        let _ = writeln!(out, "static const Stage stages_{}[] = {{", s.ident);
        for stage in &s.program.stages {
            let _ = writeln!(
                out,
                "    {{{}, {:?}, {}, {}, {}}},",
                flow_name(stage.flow),
                stage.coeff.value,
                stage.stream,
                u8::from(stage.order == SweepOrder::Reverse),
                group_name(stage.group)
            );
        }
        out.push_str("};\n\n");
    }
    out.push_str("const Scheme SCHEMES[] = {\n");
    for s in schemes {
        let _ = writeln!(
            out,
            "    {{{}, {}, {}, {}, {}, stages_{}}},",
            c_string(&s.name),
            c_string(&s.ident),
            c_string(&s.program.to_string()),
            u8::from(s.consistent),
            s.program.stages.len(),
            s.ident
        );
    }
    let _ = writeln!(out, "}};\nconst int NSCHEMES = {};\n\n}}", schemes.len());
    out
}

/// The plugin source tree for `schemes` in `dir` (created if missing), with a copy of the
/// kernels' static library `kernels` and `provenance`, one line saying what built it.
pub fn write_tree(
    dir: &Path,
    schemes: &[Exported],
    kernels: &Path,
    provenance: &str,
) -> std::io::Result<()> {
    std::fs::create_dir_all(dir.join("kernels"))?;
    for (name, text) in RUNTIME {
        std::fs::write(dir.join(name), text)?;
    }
    std::fs::write(dir.join("schemes.cpp"), schemes_cpp(schemes))?;
    std::fs::copy(kernels, dir.join(KERNELS))?;
    std::fs::write(
        dir.join("kernels/README.md"),
        format!(
            "# The dpd-lammps kernels\n\n`libdpd_lammps.a`: the pair physics of the plugin (the Rust \
             crate `dpd-lammps` of the dpd workspace, calling dpd-core's pair updates), a static \
             library with the C ABI of `../dpd_lammps.h`, licensed MIT. {provenance}\n"
        ),
    )
}

/// Identifiers made unique by a numeric suffix where two schemes would share one.
pub fn deduplicate(schemes: &mut [Exported]) {
    let mut seen = std::collections::HashSet::new();
    for s in schemes.iter_mut() {
        let base = s.ident.clone();
        let mut k = 2;
        while !seen.insert(s.ident.clone()) {
            s.ident = format!("{base}_{k}");
            k += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn registry_names_and_strings_resolve_to_their_programs() {
        let aboba = resolve("ABOBA", false).unwrap();
        assert_eq!(
            (aboba.name.as_str(), aboba.ident.as_str()),
            ("aboba", "aboba")
        );
        let y4 = resolve("S(x1) S(x0) S(x1) O", false).unwrap();
        assert_eq!(y4.ident, "s_x1_s_x0_s_x1_o");
        assert_eq!(y4.program.stages.last().unwrap().flow, Flow::O);
        let sas = resolve("sas", false).unwrap();
        assert_eq!(sas.program.stages[0].flow, Flow::T);
    }

    #[test]
    fn refusals_say_why() {
        let lowe = resolve("B A B L", false).unwrap_err();
        assert!(lowe.contains("L (Lowe-Andersen collisions)"), "{lowe}");
        for adaptive in ["B A Xi(1/2) Oa Xi(1/2) A B", "B A Xi(1/2) On Xi(1/2) A B"] {
            let e = resolve(adaptive, false).unwrap_err();
            assert!(
                e.contains("Oa or On and Xi (the adaptive thermostats"),
                "{e}"
            );
        }
        let ghmc = resolve("{B(1/2) A B(1/2)} O", false).unwrap_err();
        assert!(
            ghmc.contains("Metropolis-adjusted") && ghmc.contains("energy difference"),
            "{ghmc}"
        );
        let unknown = resolve("abobq", false).unwrap_err();
        assert!(unknown.contains("unknown scheme 'abobq'"), "{unknown}");
        let hand = resolve("setd", false).unwrap_err();
        assert!(hand.contains("hand-written"), "{hand}");
        let inconsistent = resolve("A B(1/2) O", false).unwrap_err();
        assert!(
            inconsistent.contains("--allow-inconsistent"),
            "{inconsistent}"
        );
        assert!(!resolve("A B(1/2) O", true).unwrap().consistent);
    }

    #[test]
    fn the_table_lists_every_stage_with_its_coefficient_stream_and_order() {
        let mut schemes = vec![
            resolve("BAOOAB", false).unwrap(),
            resolve("baooab", false).unwrap(),
        ];
        deduplicate(&mut schemes);
        assert_eq!(schemes[1].ident, "baooab_2");
        let cpp = schemes_cpp(&schemes);
        assert!(cpp.contains("static const Stage stages_baooab[] = {\n    {FLOW_B, 0.5, 0, 0, GROUP_ALL},\n    {FLOW_A, 0.5, 0, 0, GROUP_ALL},\n    {FLOW_O, 0.5, 0, 0, GROUP_ALL},\n    {FLOW_O, 0.5, 1, 1, GROUP_ALL},"), "{cpp}");
        assert!(cpp.contains("const int NSCHEMES = 2;"));
    }

    /// Repetition is written out and each stage carries its group; adjacent kicks of the two
    /// groups with one coefficient become one kick of all forces, others stay apart.
    #[test]
    fn force_groups_and_repetition_are_exported_with_joined_kicks() {
        let respa = resolve(
            "B[pair](1/2) (B[bond](1/8) A(1/4) B[bond](1/8))^4 O B[pair](1/2)",
            false,
        )
        .unwrap();
        let table: Vec<(Flow, Option<ForceGroup>)> = respa
            .program
            .stages
            .iter()
            .map(|s| (s.flow, s.group))
            .collect();
        let (pair, bond) = (Some(ForceGroup::Pair), Some(ForceGroup::Bond));
        let mut expected = vec![(Flow::B, pair), (Flow::B, bond)];
        for k in 0..4 {
            expected.push((Flow::A, None));
            expected.push((Flow::B, bond));
            assert_eq!(
                respa.program.stages[2 + 2 * k + 1].coeff.value,
                0.25 - (k / 3) as f64 * 0.125
            );
        }
        expected.extend([(Flow::O, None), (Flow::B, pair)]);
        assert_eq!(table, expected);
        let cpp = schemes_cpp(&[respa]);
        assert!(cpp.contains("{FLOW_B, 0.125, 0, 0, GROUP_BOND},"), "{cpp}");
        assert!(cpp.contains("{FLOW_B, 0.5, 0, 0, GROUP_PAIR},"), "{cpp}");
        // Inner count 1 of the r-RESPA splitting with O outside: OBABO's table, bit for bit.
        let one = resolve(
            "O(1/2) B[pair](1/2) (B[bond](1/2) A B[bond](1/2))^1 B[pair](1/2) O(1/2)",
            false,
        )
        .unwrap();
        let obabo = resolve("obabo", false).unwrap();
        assert_eq!(one.program.stages, obabo.program.stages);
        assert_eq!(one.program.to_string(), obabo.program.to_string());
        // Unequal coefficients or a stage between: kept apart.
        let apart = joined_kicks(
            compile_with(
                "B[pair](1/2) B[bond](1/4) A B[bond](3/4) O B[pair](1/2)",
                &Options::default(),
            )
            .unwrap(),
        );
        assert_eq!(apart.stages.iter().filter(|s| s.group.is_some()).count(), 4);
    }

    #[test]
    fn identifiers_are_c_names() {
        assert_eq!(identifier("m-shardlow-2"), "m_shardlow_2");
        assert_eq!(identifier("2 ABOBA"), "s2_aboba");
        assert_eq!(identifier("()"), "scheme");
        assert_eq!(c_string("a\"b\\c"), "\"a\\\"b\\\\c\"");
    }
}
