#!/usr/bin/env bash
# The processing search of docs/design-search.md: each scheme swept at gamma = 4.5 and 200 with
# T_C read at x + c dt^2 F(x) / m, c the one `dpd predict --processing leading` predicts cancels
# the leading dt^2 term of the T_C error (or the c given in PROCESSING, e.g. PROCESSING=0.05).
# Usage: [GAMMAS="4.5 200"] bash scripts/design/processing.sh [DPD_BINARY] [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
dpd=${1:-target/release/dpd}
out=${2:-results/design-processing}
mkdir -p "$out"
schemes=("aboba" "O B(1/2) A B(1/2)" "baoab" "A(1/2) B(1/2) O(1/2) B(1/2) A(1/2) O(1/2)")
for gamma in ${GAMMAS:-4.5 200}; do
    for i in "${!schemes[@]}"; do
        scheme=${schemes[$i]}
        c=${PROCESSING:-$("$dpd" predict "$scheme" --gamma "$gamma" --processing leading --json |
            python3 -c 'import json, sys; print(json.load(sys.stdin)["schemes"][0]["processing"])')}
        echo "gamma $gamma, $scheme: processing $c"
        "$dpd" sweep --scene "scripts/design/search-processing-gamma-$gamma.toml" \
            --schemes "$scheme" --reference "$scheme" --processing "$c" \
            --json "$out/gamma-$gamma-$i.json" --out "$out/gamma-$gamma-$i"
    done
done
