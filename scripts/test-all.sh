#!/usr/bin/env bash
# Every test the project has: formatting, lints, the Rust test suite, then each
# scripts/test-<topic>.sh (LAMMPS plugin, Python module, trajectory readers, ...), which install
# what they need into virtual environments under ${DPD_TEST_CACHE:-$HOME/.cache/dpd-test}.
# Each phase prints its wall time (CI must stay under 20 minutes).
set -euo pipefail
cd "$(dirname "$0")/.."
phase() {
    echo "== $*"
    local start=$SECONDS
    "$@"
    echo "== $* passed in $((SECONDS - start)) s"
}
phase cargo fmt --all -- --check
phase cargo clippy --workspace --all-targets --quiet -- -D warnings
# One invocation for the unit, integration and doc tests: a separate `cargo test --doc` resolves
# another unit graph for the proc macros' host dependencies and rebuilt the workspace's
# dependency graph (measured in CI: 154 s, of which the doc tests themselves ~20 s), more than
# the examples this also builds cost (~30 CPU-seconds).
phase cargo test --workspace
for script in scripts/test-*.sh; do
    [ "$script" = scripts/test-all.sh ] && continue
    phase bash "$script"
done
echo "== all passed in $SECONDS s"
