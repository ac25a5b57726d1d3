#!/usr/bin/env bash
# The KL measurements of docs/design.md ("The KL estimator") on the standard box at gamma = 4.5
# (N = 500): the ranking of symmetric schemes at dt = 0.1 and 0.07 next to their T_C errors,
# the slope of KL against dt, and the plateau in the protocol length.
# Then the lower bounds of examples/kl_bounds.rs for the same schemes.
# Usage: bash scripts/design/kl.sh [DPD_BINARY] [OUT_DIR] [KL_BOUNDS_BINARY]
# (about an hour on two cores; build both with
#  cargo build --release -p dpd-cli -p dpd --example kl_bounds)
set -euo pipefail
cd "$(dirname "$0")/../.."
dpd=${1:-target/release/dpd}
out=${2:-results/design-kl}
bounds=${3:-target/release/examples/kl_bounds}
mkdir -p "$out"
# Each measurement is skipped when its file exists, so an interrupted run resumes.
kl() { # scheme dt samples [protocol time]
    [ -s "$out/kl-$1-$2-${4:-2}.json" ] && return
    "$dpd" kl "$1" --dt "$2" --samples "$3" --protocol-time "${4:-2}" --sweeps-between 2 \
        --threads 2 --json >"$out/kl-$1-$2-${4:-2}.json"
}
tc() { # scheme dt
    [ -s "$out/tc-$1-$2.json" ] && return
    "$dpd" run --scheme "$1" --dt "$2" --time 1000 --runs 4 --threads 2 --json \
        >"$out/tc-$1-$2.json"
}
for s in aboba baoab baooab OBAB dpd-s1; do
    for dt in 0.07 0.1; do tc "$s" "$dt"; done
    kl "$s" 0.1 8000
done
for p in 1 4; do kl OBAB 0.1 4000 "$p"; done
kl OBAB 0.07 6000
kl OBAB 0.05 12000
kl aboba 0.07 40000
kl aboba 0.12 8000
kl baoab 0.07 40000
kl obabo 0.07 6000
bound() { # dt schemes...
    [ -s "$out/bounds-$1.txt" ] && return
    "$bounds" "$1" 100 4 "${@:2}" >"$out/bounds-$1.txt"
}
bound 0.1 aboba baoab baooab OBAB dpd-s1
bound 0.07 aboba baoab OBAB
bound 0.05 OBAB
