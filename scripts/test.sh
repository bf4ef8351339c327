#!/usr/bin/env bash
# Full test run: setup, Rust tests (unit, libloading host, golden XML), FMU packaging, the
# fmpy tests against the packaged FMU, and the win64 test under Wine (scripts/test-win64.sh)
# when the win64 toolchain is installed. In CI (CI=true) or with HYBEAM_WIN64=1 the toolchain
# is installed first (scripts/setup-win64.sh), so CI always runs it; HYBEAM_WIN64=0 skips it.
# Likewise HYBEAM_GLIBC=1 (CI) installs cargo-zigbuild (scripts/setup-glibc.sh): the linux64
# binaries are then linked against glibc 2.31 and checked for it (scripts/check-glibc.sh).
# Exits non-zero on any failure.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
WIN64=${HYBEAM_WIN64:-$([ "${CI:-}" = true ] && echo 1 || echo auto)}
if [ "$WIN64" = 1 ]; then
    bash scripts/setup-win64.sh
fi
GLIBC=${HYBEAM_GLIBC:-$([ "${CI:-}" = true ] && echo 1 || echo auto)}
if [ "$GLIBC" = 1 ]; then
    bash scripts/setup-glibc.sh
fi

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
PLATFORMS=$([ "$WIN64" = 0 ] && echo "--platforms linux64" || true)
for scene in ${FMU_SCENES:-$DEFAULT_SCENES}; do
    # every platform whose toolchain is installed (linux64, and win64 after setup-win64.sh)
    FMUS+=("$(cargo fmu-build "$scene" --out target/fmu $PLATFORMS | tail -n 1)")
done

if [ "$GLIBC" = 1 ]; then
    echo "== glibc floor of the linux64 binaries"
    bash scripts/check-glibc.sh "${FMUS[@]}"
fi

echo "== pytest (fmpy) on ${FMUS[*]}"
for fmu in "${FMUS[@]}"; do
    # test_view.py tests the runner's ParaView output, no FMU: run once, below
    .venv/bin/python -m pytest -q tests/python --fmu "$fmu" --ignore=tests/python/test_view.py
done
echo "== the runner's ParaView series read by PyVista/VTK (tests/python/test_view.py)"
.venv/bin/python -m pytest -q tests/python/test_view.py

echo "== Python tools: lint, format, type check (mypy), the tools' tests (python/tests)"
.venv/bin/ruff check .
.venv/bin/ruff format --check .
(cd python && ../.venv/bin/mypy)
.venv/bin/python -m pytest -q python/tests

echo "== views: the viewer bundle, the animation pages in headless Chromium"
bash scripts/test-view.sh

echo "== vehicle example: car + mounted boom co-simulation (hybeam-cosim, libcosim)"
bash examples/vehicle/run.sh --test

echo "== spatial vehicle example: four-wheel car + spatial boom (hybeam-cosim)"
bash examples/vehicle3d/run.sh --test

echo "== parameter sweeps: hybeam-sweep on a Dask LocalCluster"
bash examples/sweeps/run.sh --test

if [ "$WIN64" = 0 ]; then
    echo "== win64 test skipped (HYBEAM_WIN64=0)"
elif [ "$WIN64" = 1 ] || { [ -x /usr/bin/cargo ] && command -v x86_64-w64-mingw32-gcc >/dev/null &&
    command -v wine >/dev/null; }; then
    echo "== win64 FMU under Wine"
    bash scripts/test-win64.sh
else
    echo "== win64 test skipped: toolchain not installed (bash scripts/setup-win64.sh, or HYBEAM_WIN64=1)"
fi
