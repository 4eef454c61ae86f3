#!/usr/bin/env bash
# The main job on the bundled sample data (README: ./setup.sh demo).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BIN=$ROOT/build/bin
"$BIN/bodygen" --version
"$BIN/bodyview" --version
