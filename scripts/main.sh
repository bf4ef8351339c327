#!/usr/bin/env bash
# Main job: set up, build the FMU of a scene (default scenes/case1.toml), simulate it with fmpy,
# write out/<scene>_tip.csv (every output) and out/<scene>_tip.png (tip deflection: y for a
# planar scene, y and z for a spatial one, e.g. scenes/case1_3d.toml).
# Usage: scripts/main.sh [SCENE.toml]   (default scenes/case1.toml)
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-scenes/case1.toml}
id=$(basename "$scene" .toml)
bash scripts/setup.sh
mkdir -p out
fmu=$(cargo fmu-build "$scene" --out out | tail -n 1)
.venv/bin/python scripts/simulate_fmu.py "$fmu" --out "out/${id}_tip"
