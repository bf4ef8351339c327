#!/usr/bin/env bash
# Main job: set up, build the Case 1 FMU from scenes/case1.toml, simulate it with fmpy, write
# out/case1_tip.csv and out/case1_tip.png (vertical tip deflection).
# Usage: scripts/main.sh [SCENE.toml]   (default scenes/case1.toml)
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-scenes/case1.toml}
id=$(basename "$scene" .toml)
bash scripts/setup.sh
mkdir -p out
fmu=$(cargo fmu-build "$scene" --out out | tail -n 1)
.venv/bin/python scripts/simulate_fmu.py "$fmu" --out "out/${id}_tip"
