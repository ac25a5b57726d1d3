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
# The examples are not built here: clippy --all-targets has type-checked them, and their code
# generation and linking cost ~30 CPU-seconds that no test uses (quick_start, which README shows,
# is compiled into tests/readme.rs).
phase cargo test --workspace --lib --bins --tests
phase cargo test --workspace --doc
for script in scripts/test-*.sh; do
    [ "$script" = scripts/test-all.sh ] && continue
    phase bash "$script"
done
echo "== all passed in $SECONDS s"
