#!/usr/bin/env bash
# dpd-core's top-level modules import one another without a cycle (issue 24): the state sits
# below the flows, schemes and observables that use it (docs/architecture.md, "Layers").
# dpd-measure's files import one another without a cycle (issue 50), parents and children
# included: a scene section, an observer or a paper file never reaches back to what lists it.
set -euo pipefail
cd "$(dirname "$0")/.."
python3 scripts/module_graph.py dpd-core/src
python3 scripts/module_graph.py dpd-measure/src --files
