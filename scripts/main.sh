#!/usr/bin/env bash
# The main job: builds everything and runs the demo, which writes its figures to out/.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
leuven-rt demo --out out
