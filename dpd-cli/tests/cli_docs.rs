//! docs/cli.md and docs/scenes.md cannot drift from the program: each flag of each command
//! (read from its `--help`) is named in the command's section of docs/cli.md, or for the scene
//! flags in docs/scenes.md, and each flag a section names exists; the scene table of
//! docs/scenes.md lists every scene key with its flag; and each JSON field table of docs/cli.md
//! lists exactly the fields the program writes there.
use super::cli_support;

use cli_support::{dpd, json, write};
use serde_json::Value;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

const CLI_MD: &str = include_str!("../../docs/cli.md");
const SCENES_MD: &str = include_str!("../../docs/scenes.md");

type Names = BTreeSet<String>;

/// `dpd ARGS --help`.
fn help(args: &[&str]) -> String {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = dpd(dir, &[args, &["--help"]].concat());
    assert!(out.status.success(), "dpd {args:?} --help");
    String::from_utf8(out.stdout).unwrap()
}

/// The long flags (without `--help`, `--version`) and the subcommands (without clap's `help`)
/// of a help text.
fn parse_help(text: &str) -> (Names, Vec<String>) {
    let (mut flags, mut commands) = (Names::new(), Vec::new());
    let mut in_commands = false;
    for line in text.lines() {
        if !line.starts_with(' ') {
            in_commands = line == "Commands:";
            continue;
        }
        let item = line.trim_start();
        if in_commands {
            let name = item.split_whitespace().next().unwrap_or("");
            if name != "help" {
                commands.push(name.to_string());
            }
        } else if let Some(rest) = item
            .strip_prefix("--")
            .or_else(|| item.split_once(", --").map(|(_, r)| r))
        {
            let flag: String = rest
                .chars()
                .take_while(|c| *c != ' ' && *c != '<')
                .collect();
            if flag != "help" && flag != "version" {
                flags.insert(flag);
            }
        }
    }
    (flags, commands)
}

/// Every command without subcommands ("run", "export lammps", ...) with its flags.
fn commands() -> BTreeMap<String, Names> {
    let mut found = BTreeMap::new();
    let mut todo = vec![Vec::<String>::new()];
    while let Some(path) = todo.pop() {
        let args: Vec<&str> = path.iter().map(String::as_str).collect();
        let (flags, subcommands) = parse_help(&help(&args));
        if subcommands.is_empty() {
            found.insert(path.join(" "), flags);
        }
        for s in subcommands {
            todo.push([path.clone(), vec![s]].concat());
        }
    }
    found
}

/// The `## ` sections of docs/cli.md: heading and body.
fn sections() -> Vec<(&'static str, &'static str)> {
    CLI_MD
        .split("\n## ")
        .skip(1)
        .map(|s| s.split_once('\n').unwrap_or((s, "")))
        .collect()
}

/// The command a heading documents: "`dpd export lammps SCHEME... --out DIR`" is
/// "export lammps" (the lowercase words after `dpd`).
fn command_of(heading: &str) -> Option<String> {
    let rest = heading.strip_prefix("`dpd ")?;
    let words: Vec<&str> = rest
        .split([' ', '`'])
        .take_while(|w| !w.is_empty() && w.chars().all(|c| c.is_ascii_lowercase()))
        .collect();
    Some(words.join(" "))
}

/// The page of the scene keys.
fn scenes_section() -> &'static str {
    SCENES_MD
}

/// Every `--flag` named in `text`.
fn flags_in(text: &str) -> Names {
    text.split("--")
        .skip(1)
        .map(|s| {
            s.chars()
                .take_while(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || *c == '-')
                .collect::<String>()
        })
        .filter(|f| f.starts_with(|c: char| c.is_ascii_lowercase()) && f != "help")
        .collect()
}

/// The backticked words of a table cell that are names (`scheme`, `dt_min`), in order; a
/// `[table]` comes out with its brackets.
fn names_in(cell: &str) -> Vec<String> {
    cell.split('`')
        .skip(1)
        .step_by(2)
        .filter(|w| {
            let w = w.trim_start_matches('[').trim_end_matches(']');
            !w.is_empty()
                && w.chars()
                    .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
        })
        .map(str::to_string)
        .collect()
}

/// The tables of `text`: header cells, then the rows' cells.
fn tables(text: &str) -> Vec<(Vec<String>, Vec<Vec<String>>)> {
    let cells = |line: &str| -> Vec<String> {
        line.trim()
            .trim_matches('|')
            .split(" | ")
            .map(|c| c.trim().to_string())
            .collect()
    };
    let mut found = Vec::new();
    let lines: Vec<&str> = text.lines().collect();
    let mut i = 0;
    while i + 1 < lines.len() {
        if lines[i].starts_with('|') && lines[i + 1].starts_with("|---") {
            let header = cells(lines[i]);
            let rows = lines[i + 2..]
                .iter()
                .take_while(|l| l.starts_with('|'))
                .map(|l| cells(l))
                .collect::<Vec<_>>();
            i += 2 + rows.len();
            found.push((header, rows));
        } else {
            i += 1;
        }
    }
    found
}

#[test]
fn every_flag_is_documented_in_its_section_and_every_documented_flag_exists() {
    let commands = commands();
    let sections = sections();
    let scene_flags = flags_in(scenes_section());
    for flag in &scene_flags {
        assert!(
            commands["run"].contains(flag),
            "docs/scenes.md names --{flag}, which `dpd run` does not have"
        );
    }
    for (command, flags) in &commands {
        let (heading, body) = sections
            .iter()
            .find(|(h, _)| command_of(h).as_deref() == Some(command.as_str()))
            .unwrap_or_else(|| panic!("docs/cli.md has no section `## `dpd {command} ...``"));
        let named: Names = flags_in(heading).union(&flags_in(body)).cloned().collect();
        let elsewhere = if flags.contains("scene") {
            &scene_flags
        } else {
            &Names::new()
        };
        let missing: Vec<_> = flags
            .iter()
            .filter(|f| !named.contains(*f) && !elsewhere.contains(*f))
            .collect();
        assert!(
            missing.is_empty(),
            "docs/cli.md's section on `dpd {command}` lacks {missing:?}"
        );
        let unknown: Vec<_> = named.difference(flags).collect();
        assert!(
            unknown.is_empty(),
            "docs/cli.md's section on `dpd {command}` names flags it does not have: {unknown:?}"
        );
    }
}

/// The scene table of docs/scenes.md: per row, the key names (a `[table]` first for the keys of
/// a table) and the flags of the flag column.
fn scene_table() -> Vec<(Vec<String>, Names)> {
    let (header, rows) = tables(scenes_section())
        .into_iter()
        .find(|(h, _)| h[0] == "key" && h[1] == "flag")
        .expect("docs/scenes.md has a table `| key | flag | ...`");
    assert_eq!(header.len(), 4);
    rows.iter()
        .map(|r| (names_in(&r[0]), flags_in(&r[1])))
        .collect()
}

/// The keys of every object in `values`, `null` skipped.
fn keys(values: &[&Value]) -> Names {
    values
        .iter()
        .filter_map(|v| v.as_object())
        .flat_map(|o| o.keys().cloned())
        .collect()
}

/// What a scene table's keys are read from: an array of tables (`[[species]]`) its tables, a
/// table of tables keyed by the user's names (`[pairs]`, keyed `A-B`) those tables, any other
/// table itself.
fn entries(v: &Value) -> Vec<&Value> {
    match v {
        Value::Array(items) => items.iter().collect(),
        Value::Object(o) if !o.is_empty() && o.values().all(Value::is_object) => {
            o.values().collect()
        }
        v => vec![v],
    }
}

/// The elements of the array `v[key]`.
fn each<'a>(v: &'a Value, key: &str) -> Vec<&'a Value> {
    v[key]
        .as_array()
        .unwrap_or_else(|| panic!("{key} is not an array in {v}"))
        .iter()
        .collect()
}

/// The outputs the documented fields are compared with, keyed by the first header cell of
/// their table in docs/cli.md. Small runs: 100 particles, a few time units.
fn outputs() -> BTreeMap<&'static str, Vec<Value>> {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let tiny = "n = 100\ntime = 1.0\naverage_fraction = 0.5\n";
    let observed = write(
        d,
        "observed.toml",
        &format!(
            "{tiny}energy_balance = true\nprocessing = 0.1\n[rdf]\nr_max = 1.5\nbins = 10\ninterval = 0.2\n\
             [vacf]\nmax_lag = 0.3\norigin_every = 2\n[trajectory]\nfile = \"t.xyz\"\n\
             every = 0.5\n"
        ),
    );
    let channel = write(
        d,
        "channel.toml",
        "box = [3.0, 3.0, 6.0]\ntime = 0.5\naverage_fraction = 0.5\nbody_force = 0.1\n\
         [walls]\nlower = 1.0\nupper = 5.0\nvelocity = [0.0, 0.0]\n[profile]\nbins = 4\n",
    );
    // Long enough for a viscosity, which the rows' relative error needs.
    let sheared = write(
        d,
        "sheared.toml",
        "n = 100\ntime = 4.0\naverage_fraction = 0.5\nshear_rate = 0.5\n[profile]\nbins = 4\n\
         [sweep]\nschemes = [\"vv\", \"aboba\"]\ndt_min = 0.02\ndt_max = 0.025\n\
         observable = \"viscosity\"\n",
    );
    let grid = write(
        d,
        "grid.toml",
        &format!("{tiny}[sweep]\ndt_min = 0.04\ndt_max = 0.07\ndt_factor = 1.5\n"),
    );
    let mixture = write(
        d,
        "mixture.toml",
        &format!(
            "{tiny}like_neighbours = true\n[rdf]\nr_max = 1.5\nbins = 5\n[profile]\nbins = 2\n\
             [[species]]\nname = \"A\"\nfraction = 0.5\nmass = 2.0\n[[species]]\n\
             name = \"B\"\nfraction = 0.5\n[pairs]\nA-A = {{ a = 25.0 }}\n\
             B-B = {{ a = 25.0 }}\nA-B = {{ a = 40.0, gamma = 9.0, rc = 0.9 }}\n"
        ),
    );
    let melt = write(
        d,
        "melt.toml",
        &format!(
            "{tiny}exclude_bonded = true\n\
             [[bond_types]]\nname = \"h\"\nstyle = \"harmonic\"\nk = 2.0\nr0 = 0.5\n\
             [[bond_types]]\nname = \"f\"\nstyle = \"fene\"\nk = 30.0\nr_max = 1.5\n\
             [[angle_types]]\nname = \"c\"\nstyle = \"cosine_squared\"\nk = 2.0\n\
             theta0 = 120.0\n\
             [[molecules]]\nlength = 4\ncount = 5\nbeads = \"A\"\nbond = \"h\"\n\
             angle = \"c\"\nstep = 0.6\n\
             [[molecules]]\nlength = 5\nfraction = 0.5\nbond = \"f\"\n"
        ),
    );
    // A Metropolis-adjusted scheme reports its acceptance.
    let adjusted = write(
        d,
        "adjusted.toml",
        &format!("{tiny}scheme = \"{{B(1/2) A B(1/2)}} O\"\n"),
    );
    let run = |scene: &str| json(&dpd(d, &["run", "--scene", scene, "--json"]));
    let runs = [
        run(&observed),
        run(&channel),
        run(&mixture),
        run(&melt),
        run(&adjusted),
    ];
    let sweep_out = dpd(d, &["sweep", "--scene", &sheared, "--json", "s.json"]);
    assert!(sweep_out.status.success(), "{sweep_out:?}");
    let sweep: Value = serde_json::from_slice(&std::fs::read(d.join("s.json")).unwrap()).unwrap();
    let palindrome = "param l in 0..1/2; B(l) A(1/2) B(1 - 2*l) A(1/2) B(l) O";
    let limit = "param c in 0..1; A(1/2) B(1/2) O(c) B(1/2) A(1/2) O(1 - c)";
    let designs = [
        json(&dpd(
            d,
            &[
                "design",
                palindrome,
                "--measure",
                "--top",
                "1",
                "--scene",
                &grid,
                "--json",
            ],
        )),
        json(&dpd(d, &["design", limit, "--json"])),
    ];
    let check_args = [
        vec!["check", "BAOOAB", "--json"],
        vec!["check", palindrome, "--at", "0.2", "--json"],
    ];
    let checks: Vec<Value> = check_args.iter().map(|a| json(&dpd(d, a))).collect();
    let orderings = [
        json(&dpd(d, &["orderings", "--max-len", "3", "--json"])),
        json(&dpd(
            d,
            &[
                "orderings",
                "--max-len",
                "3",
                "--rank",
                "predicted",
                "--spectrum-particles",
                "64",
                "--json",
            ],
        )),
    ];
    let predict = json(&dpd(
        d,
        &[
            "predict",
            "aboba",
            "vv",
            "--dt",
            "0.05,0.5",
            "--spectrum-particles",
            "64",
            "--json",
        ],
    ));
    let predicted = json(&dpd(
        d,
        &["design", palindrome, "--objective", "predicted", "--json"],
    ));
    let schemes = json(&dpd(d, &["schemes", "--json"]));
    let kl = json(&dpd(
        d,
        &[
            "kl",
            "ABOBA",
            "--n",
            "100",
            "--samples",
            "20",
            "--protocol-time",
            "0.2",
            "--json",
        ],
    ));
    let stability = json(&dpd(
        d,
        &["stability", "--reduced", "--schemes", "aboba", "--json"],
    ));

    let owned = |v: Vec<&Value>| v.into_iter().cloned().collect::<Vec<Value>>();
    let mut rows: Vec<&Value> = runs.iter().collect();
    rows.extend(each(&sweep, "rows"));
    rows.push(&sweep["baseline"]);
    let mut points: Vec<&Value> = runs.iter().flat_map(|r| each(r, "results")).collect();
    points.extend(each(&sweep, "points"));
    let members: Vec<&Value> = designs
        .iter()
        .flat_map(|d| [each(d, "solutions"), each(d, "notable")].concat())
        .collect();
    let list = |v: &Value| v.as_array().unwrap().clone();
    BTreeMap::from([
        (
            "field of `dpd run --json` and of a sweep's `rows` and `baseline`",
            owned(rows),
        ),
        (
            "field of `dpd run --json`'s `results` and of a sweep's `points` (one run)",
            owned(points),
        ),
        ("field of the sweep's results file", vec![sweep.clone()]),
        (
            "field of the sweep's `summary` (one scheme)",
            owned(each(&sweep, "summary")),
        ),
        ("field of `dpd check --json`", checks),
        (
            "field of `dpd orderings --json` (one ordering)",
            orderings.iter().flat_map(list).collect(),
        ),
        ("field of `dpd predict --json`", vec![predict.clone()]),
        (
            "field of `dpd predict --json`'s `schemes` (one scheme)",
            owned(each(&predict, "schemes")),
        ),
        (
            "field of `dpd predict --json`'s `rows` (one dt)",
            owned(
                each(&predict, "schemes")
                    .into_iter()
                    .flat_map(|s| each(s, "rows"))
                    .collect(),
            ),
        ),
        (
            "field of `dpd design --objective predicted --json`'s `predicted`",
            vec![predicted["predicted"].clone()],
        ),
        ("field of `dpd schemes --json` (one scheme)", list(&schemes)),
        (
            "field of `dpd design --json`",
            [designs.to_vec(), vec![predicted["design"].clone()]].concat(),
        ),
        (
            "field of a `dpd design --json` member (`solutions`, `notable`)",
            owned(members),
        ),
        (
            "field of `dpd design --json`'s `measured` (one scheme)",
            owned(each(&designs[0], "measured")),
        ),
        ("field of `dpd kl --json`", vec![kl]),
        ("field of `dpd stability --json`", vec![stability.clone()]),
        (
            "field of `dpd stability --json`'s `matrix`",
            vec![stability["matrix"].clone()],
        ),
        (
            "field of `dpd stability --json`'s `records` (one run)",
            owned(each(&stability, "records")),
        ),
        // Not a field table: the scenes written back by `dpd run` and `dpd sweep`.
        (
            "scene",
            owned([runs.iter().collect::<Vec<_>>(), vec![&sweep]].concat())
                .into_iter()
                .map(|v| v["scene"].clone())
                .collect(),
        ),
    ])
}

#[test]
fn every_json_field_and_scene_key_is_documented_and_every_documented_one_is_written() {
    let mut outputs = outputs();
    let scenes = outputs.remove("scene").unwrap();

    // The field tables: `| field of ... | meaning |`.
    let documented: BTreeMap<String, Names> = tables(CLI_MD)
        .into_iter()
        .filter(|(h, _)| h[0].starts_with("field of ") && h.len() == 2)
        .map(|(h, rows)| {
            (
                h[0].clone(),
                rows.iter().flat_map(|r| names_in(&r[0])).collect(),
            )
        })
        .collect();
    let tables: Names = documented.keys().cloned().collect();
    let known: Names = outputs.keys().map(|k| k.to_string()).collect();
    assert_eq!(
        tables, known,
        "docs/cli.md's JSON field tables and the outputs this test compares them with"
    );
    for (table, values) in &outputs {
        let written = keys(&values.iter().collect::<Vec<_>>());
        let doc = &documented[*table];
        let undocumented: Vec<_> = written.difference(doc).collect();
        let unwritten: Vec<_> = doc.difference(&written).collect();
        assert!(
            undocumented.is_empty() && unwritten.is_empty(),
            "docs/cli.md, table `{table}`: fields written but not documented {undocumented:?}, \
             documented but not written {unwritten:?}"
        );
    }

    // The scene table: its keys are those of the scenes written back, table by table.
    let rows = scene_table();
    let scene_refs: Vec<&Value> = scenes.iter().collect();
    let top: Names = rows
        .iter()
        .flat_map(|(names, _)| match names[0].starts_with('[') {
            true => vec![names[0].trim_matches(['[', ']']).to_string()],
            false => names.clone(),
        })
        .collect();
    assert_eq!(
        top,
        keys(&scene_refs),
        "docs/scenes.md's scene table and the keys of a scene"
    );
    for (names, _) in rows.iter().filter(|(n, _)| n[0].starts_with('[')) {
        let table = names[0].trim_matches(['[', ']']);
        let sub: Vec<&Value> = scenes.iter().flat_map(|s| entries(&s[table])).collect();
        let doc: Names = names[1..].iter().cloned().collect();
        assert_eq!(
            doc,
            keys(&sub),
            "docs/scenes.md's scene table, `[{table}]`, and the keys of that table"
        );
    }

    // Its flag column: a key's flag where `dpd run` has one; other flags only beside tables.
    let run_flags = &commands()["run"];
    for (names, flags) in &rows {
        for flag in flags {
            assert!(run_flags.contains(flag), "scene table: no flag --{flag}");
        }
        if names[0].starts_with('[') {
            continue;
        }
        let expected: Names = names
            .iter()
            .map(|k| k.replace('_', "-"))
            .filter(|f| run_flags.contains(f))
            .collect();
        assert_eq!(
            flags, &expected,
            "docs/scenes.md's scene table, the flag column of {names:?}"
        );
    }
}

/// Every `dpd ...` command line of README.md and docs/*.md (the dated notes aside): in
/// backticks, or a line of a code block; `cargo run --release -- ARGS` counts as `dpd ARGS`.
fn command_lines() -> Vec<(String, String)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut files = vec![root.join("README.md")];
    let mut docs: Vec<_> = std::fs::read_dir(root.join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    files.extend(docs);
    let mut found = Vec::new();
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        let name = file.file_name().unwrap().to_string_lossy().to_string();
        let spans = text.split('`').skip(1).step_by(2);
        let lines = text.lines().map(|l| l.split('#').next().unwrap().trim());
        for candidate in spans.chain(lines) {
            let candidate = candidate.replace("cargo run --release -- ", "dpd ");
            if candidate.starts_with("dpd ") {
                found.push((name.clone(), candidate));
            }
        }
    }
    found
}

#[test]
fn every_command_line_in_the_docs_uses_flags_its_command_has() {
    let commands = commands();
    let mut checked = 0;
    for (file, line) in command_lines() {
        let words: Vec<&str> = line.split_whitespace().skip(1).collect();
        let Some(first) = words.first() else { continue };
        if !first.chars().all(|c| c.is_ascii_lowercase()) {
            continue; // `dpd COMMAND --help`, `dpd = { path = ... }`
        }
        let two = words[..2.min(words.len())].join(" ");
        let command = [two.as_str(), first]
            .into_iter()
            .find(|c| commands.contains_key(*c))
            .unwrap_or_else(|| panic!("{file}: `{line}` names no command of dpd"));
        let unknown: Vec<_> = flags_in(&line)
            .into_iter()
            .filter(|f| !commands[command].contains(f))
            .collect();
        assert!(
            unknown.is_empty(),
            "{file}: `{line}` uses flags `dpd {command}` does not have: {unknown:?}"
        );
        checked += 1;
    }
    assert!(checked > 50, "only {checked} command lines found");
}
