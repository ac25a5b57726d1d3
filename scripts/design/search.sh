#!/usr/bin/env bash
# The search of docs/design.md: sweeps of one-force-evaluation splittings (and a few
# multi-force schemes, compared per unit of cost) against ABOBA at gamma = 4.5 and 200.
# Usage: bash scripts/design/search.sh [DPD_BINARY] [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
dpd=${1:-target/release/dpd}
out=${2:-results/design-search}
for gamma in 4.5 200; do
    "$dpd" sweep --scene "scripts/design/search-gamma-$gamma.toml" \
        --json "$out/gamma-$gamma.json" --out "$out/gamma-$gamma"
done
