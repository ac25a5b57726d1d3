#!/usr/bin/env bash
# The Python module (python/, issue 27): `pip install ./python` into a virtual environment under
# ${DPD_TEST_CACHE:-$HOME/.cache/dpd-test} (reused if present) and its pytest suite. The crate is
# a workspace member, formatted and linted with the rest by scripts/test-all.sh. maturin builds it
# with the settings of the `test` profile (optimised, as users' release builds are) so that it
# reuses what `cargo test --workspace` compiled instead of compiling every dependency again:
# `--profile test` itself would build a test harness, but `test` is `dev` with opt-level 3, and
# cargo identifies artifacts by their settings, not by the profile's name
# (and the features it resolves for -p dpd-python match the workspace's: workspace-hack/).
set -euo pipefail
cd "$(dirname "$0")/.."
cache="${DPD_TEST_CACHE:-$HOME/.cache/dpd-test}"
venv="$cache/python-venv"
# maturin, the build backend, is found on PATH.
export PATH="$venv/bin:$PATH"
if [ ! -x "$venv/bin/pytest" ]; then
    python3 -m venv "$venv"
    "$venv/bin/pip" install --quiet maturin==1.8.6 numpy==2.2.6 pytest==8.3.5
fi
CARGO_PROFILE_DEV_OPT_LEVEL=3 MATURIN_PEP517_ARGS="--profile dev" "$venv/bin/pip" install --quiet --no-build-isolation --force-reinstall --no-deps ./python
# pytest exits with 5 when it collects no test: a failure here like any other non-zero code.
"$venv/bin/pytest" -q python/tests
