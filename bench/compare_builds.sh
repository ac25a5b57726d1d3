#!/usr/bin/env bash
# Two builds side by side: the state hash of `examples/state_hash` (bitwise the same trajectory
# or not) and the instructions of the steps (cachegrind, a run of STEPS steps less a run of
# none, so that the set-up does not count), for velocity Verlet, ABOBA, DPD-S1 and DPD-Trotter
# (sas) on the periodic, sheared, walled and two-type systems of that example. Instruction
# counts do not depend on the machine's load; the hashes are compared on 1 and 2 threads.
#
# Usage: bench/compare_builds.sh BEFORE AFTER [N] [STEPS]
#   BEFORE, AFTER: two `state_hash` executables, e.g. `target/release/examples/state_hash` of
#   two commits copied aside (`cargo build --release -p dpd --example state_hash`).
set -euo pipefail
before=$1
after=$2
n=${3:-4000}
steps=${4:-40}

# The instructions `valgrind --tool=cachegrind` counts for one run.
instructions() {
  local out
  out=$(mktemp)
  valgrind --tool=cachegrind --cache-sim=no --cachegrind-out-file=/dev/null "$@" \
    >/dev/null 2>"$out"
  sed -n 's/.*I *refs: *\([0-9,]*\).*/\1/p' "$out" | tr -d ,
  rm -f "$out"
}

printf '%-7s %-10s %-7s %-18s %-18s %14s %14s %8s\n' scheme system threads \
  "hash before" "hash after" "instr before" "instr after" ratio
status=0
for system in periodic sheared walled two-types; do
  for scheme in vv aboba dpd-s1 sas; do
    for threads in 1 2; do
      hb=$("$before" "$n" "$steps" "$threads" 0 "$scheme" "$system" | sed 's/.*hash=//')
      ha=$("$after" "$n" "$steps" "$threads" 0 "$scheme" "$system" | sed 's/.*hash=//')
      [ "$hb" = "$ha" ] || status=1
      if [ "$threads" = 1 ]; then
        ib=$(($(instructions "$before" "$n" "$steps" 1 0 "$scheme" "$system") -
          $(instructions "$before" "$n" 0 1 0 "$scheme" "$system")))
        ia=$(($(instructions "$after" "$n" "$steps" 1 0 "$scheme" "$system") -
          $(instructions "$after" "$n" 0 1 0 "$scheme" "$system")))
        ratio=$(python3 -c "print(f'{$ia / $ib:.4f}')")
      else
        ib=- ia=- ratio=-
      fi
      printf '%-7s %-10s %-7s %-18s %-18s %14s %14s %8s\n' "$scheme" "$system" "$threads" \
        "$hb" "$ha" "$ib" "$ia" "$ratio"
    done
  done
done
[ "$status" = 0 ] && echo "every hash equal" || echo "HASHES DIFFER"
exit "$status"
