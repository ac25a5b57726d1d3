#!/usr/bin/env bash
# The search of docs/design-search.md: sweeps of one-force-evaluation splittings (and a few
# multi-force schemes, compared per unit of cost) against ABOBA at gamma = 4.5 and 200, and the
# Lowe-Andersen schemes at the matched collision rates, the adaptive (PAdL) schemes and the
# Metropolis-adjusted one (GHMC), Peters' scheme and the pairwise Nose-Hoover-Langevin (PNHL)
# ones (processed observables: processing.sh).
# Usage: bash scripts/design/search.sh [DPD_BINARY] [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
dpd=${1:-target/release/dpd}
out=${2:-results/design-search}
for gamma in 4.5 200; do
    for scene in search search-lowe search-padl search-ghmc search-peters search-pnhl; do
        "$dpd" sweep --scene "scripts/design/$scene-gamma-$gamma.toml" \
            --json "$out/$scene-gamma-$gamma.json" --out "$out/$scene-gamma-$gamma"
    done
done
