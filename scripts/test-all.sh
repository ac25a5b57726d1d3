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
# The scripts' virtual environments download while the Rust suite compiles (scripts/venvs.sh).
venvs_log=$(mktemp)
trap 'rm -f "$venvs_log"' EXIT
bash scripts/venvs.sh lammps python trajectory >"$venvs_log" 2>&1 &
venvs=$!
phase cargo fmt --all -- --check
phase cargo clippy --workspace --all-targets --quiet -- -D warnings
# One invocation for the unit, integration and doc tests: a separate `cargo test --doc` resolves
# another unit graph for the proc macros' host dependencies and rebuilt the workspace's
# dependency graph (measured in CI: 154 s, of which the doc tests themselves ~20 s), more than
# the examples this also builds cost (48 s of unit time at -j1, docs/notes/2026-12-07-ci-time.md).
phase cargo test --workspace
venvs_installed() {
    wait "$venvs" || { cat "$venvs_log"; return 1; }
}
phase venvs_installed
for script in scripts/test-*.sh; do
    [ "$script" = scripts/test-all.sh ] && continue
    phase bash "$script"
done
echo "== all passed in $SECONDS s"
