#!/usr/bin/env bash
# Full test run: setup, Rust tests (unit, libloading host, golden XML), FMU packaging, and the
# fmpy tests against the packaged FMU. Exits non-zero on any failure.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh

echo "== cargo test --workspace"
cargo test --workspace

echo "== release runner (the fmpy tests compare the FMU with it)"
cargo build --release --bin hybeam

echo "== packaging FMUs"
mkdir -p target/fmu
FMUS=()
# The shipped scenes are those with a golden modelDescription/<id>.xml;
# FMU_SCENES="scenes/a.toml scenes/b.toml" overrides the list.
DEFAULT_SCENES=""
for golden in modelDescription/*.xml; do
    DEFAULT_SCENES+=" scenes/$(basename "$golden" .xml).toml"
done
for scene in ${FMU_SCENES:-$DEFAULT_SCENES}; do
    FMUS+=("$(cargo fmu-build "$scene" --out target/fmu | tail -n 1)")
done

echo "== pytest (fmpy) on ${FMUS[*]}"
for fmu in "${FMUS[@]}"; do
    .venv/bin/python -m pytest -q tests/python --fmu "$fmu"
done
