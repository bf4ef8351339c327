#!/usr/bin/env bash
# Full test run: setup, Rust tests (unit, libloading host, golden XML), FMU packaging, and the
# fmpy tests against the packaged FMU. Exits non-zero on any failure.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh

echo "== cargo test --workspace"
cargo test --workspace

echo "== packaging FMUs"
mkdir -p target/fmu
FMUS=()
# FMU_SCENES="scenes/a.toml scenes/b.toml" restricts the scenes packaged and tested.
for scene in ${FMU_SCENES:-scenes/*.toml}; do
    FMUS+=("$(cargo fmu-build "$scene" --out target/fmu | tail -n 1)")
done

echo "== pytest (fmpy) on ${FMUS[*]}"
for fmu in "${FMUS[@]}"; do
    .venv/bin/python -m pytest -q tests/python --fmu "$fmu"
done
