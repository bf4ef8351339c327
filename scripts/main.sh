#!/usr/bin/env bash
# Main job: set up, build the FMU of a scene (default scenes/case1.toml), simulate it with fmpy,
# write out/<scene>_tip.csv (every output) and out/<scene>_tip.png (tip deflection: y for a
# planar scene, y and z for a spatial one, e.g. scenes/case1_3d.toml); the FMU itself writes the
# beam's shape into out/<scene>_view/: a ParaView series (*.pvd of *.vtu) and the animation
# page (*.html, open it in a browser; docs/view.md).
# Usage: scripts/main.sh [SCENE.toml]   (default scenes/case1.toml)
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-scenes/case1.toml}
id=$(basename "$scene" .toml)
bash scripts/setup.sh --main
mkdir -p out
fmu=$(cargo fmu-build "$scene" --out out | tail -n 1)
rm -rf "out/${id}_view"
.venv/bin/python scripts/simulate_fmu.py "$fmu" --out "out/${id}_tip" --view "out/${id}_view"
