#!/usr/bin/env bash
# A crate whose integration tests build as one binary (tests/suite.rs, `autotests = false`)
# compiles only the files suite.rs declares: a file added under tests/ and not declared there
# would never run. Fail on any such file.
set -euo pipefail
cd "$(dirname "$0")/.."
missing=0
for suite in */tests/suite.rs; do
    dir=$(dirname "$suite")
    for file in "$dir"/*.rs; do
        name=$(basename "$file" .rs)
        [ "$name" = suite ] && continue
        if ! grep -q "^mod $name;" "$suite"; then
            echo "$file is not a module of $suite: add \`mod $name;\` there" >&2
            missing=1
        fi
    done
done
exit $missing
