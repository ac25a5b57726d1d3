#!/usr/bin/env bash
# The Python module (python/, issue 27): formatting and lints of its crate, then
# `pip install ./python` into a virtual environment under ${DPD_TEST_CACHE:-$HOME/.cache/dpd-test}
# (reused if present, with its own cargo target directory) and its pytest suite.
set -euo pipefail
cd "$(dirname "$0")/.."
cache="${DPD_TEST_CACHE:-$HOME/.cache/dpd-test}"
venv="$cache/python-venv"
export CARGO_TARGET_DIR="$cache/python-target"
# maturin, the build backend, is found on PATH.
export PATH="$venv/bin:$PATH"
cargo fmt --manifest-path python/Cargo.toml -- --check
cargo clippy --manifest-path python/Cargo.toml --quiet -- -D warnings
if [ ! -x "$venv/bin/pytest" ]; then
    python3 -m venv "$venv"
    "$venv/bin/pip" install --quiet maturin==1.8.6 numpy==2.2.6 pytest==8.3.5 matplotlib==3.10.3
fi
"$venv/bin/pip" install --quiet --no-build-isolation --force-reinstall --no-deps ./python
# pytest exits with 5 when it collects no test: a failure here like any other non-zero code.
"$venv/bin/pytest" -q python/tests
