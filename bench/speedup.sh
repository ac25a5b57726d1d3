#!/usr/bin/env bash
# Parallel speed-up of velocity Verlet and ABOBA: `examples/step_timing` on one thread and on
# all threads, taking turns ROUNDS times (default 6), so that a slow spell of a shared machine
# hits both sides of a ratio alike. Per scheme it prints the per-round speed-ups, from the
# mean time per step and from the fastest 10-step block of each run, and their medians.
#
# Usage: [ROUNDS=6] bench/speedup.sh [N] [STEPS]
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-192000}
steps=${2:-30}
rounds=${ROUNDS:-6}
all=$(nproc)

cargo build --release --quiet -p dpd --example step_timing
out=$(mktemp)
for round in $(seq "$rounds"); do
  for scheme in vv aboba; do
    for threads in 1 "$all"; do
      "${CARGO_TARGET_DIR:-target}/release/examples/step_timing" "$n" "$steps" "$threads" 0.0 "$scheme" \
        | sed "s/^{/{\"round\": $round, /" | tee -a "$out"
    done
  done
done
python3 - "$out" "$all" <<'PY'
import json, statistics, sys
rows = [json.loads(l) for l in open(sys.argv[1]) if l.strip()]
all_threads = int(sys.argv[2])
at = {(r["scheme"], r["round"], r["threads"]): r for r in rows}
print(f"\nspeed-up on {all_threads} threads over 1, N = {rows[0]['n']}")
for scheme in sorted({r["scheme"] for r in rows}):
    rounds = sorted({r["round"] for r in rows if r["scheme"] == scheme})
    for key, label in (("ns_per_particle_step", "mean"), ("fastest_block_ns_per_particle_step", "fastest block")):
        ratios = [at[(scheme, k, 1)][key] / at[(scheme, k, all_threads)][key] for k in rounds]
        each = " ".join(f"{x:.2f}" for x in ratios)
        print(f"{scheme:16} {label:14} median {statistics.median(ratios):.2f}  per round {each}")
PY
rm -f "$out"
