#!/usr/bin/env bash
# Idempotent setup on a fresh Debian machine with rustup's toolchain and python3 (3.11):
# libclang-dev (fmi-sys runs bindgen in the tests), a .venv with the pinned Python tools, the
# views' browser test (Chromium, Node.js, the viewer's npm packages). Nothing is compiled here:
# each command compiles what it needs (scripts/test.sh: cargo test; cargo fmu-build: the engine
# once, in the FMU's profile).
#   --main   only what the main job needs (scripts/main.sh): the .venv with fmpy, numpy and
#            matplotlib
set -euo pipefail
cd "$(dirname "$0")/.."
MAIN=0
if [ "${1:-}" = --main ]; then MAIN=1; fi

FMPY_VERSION=0.3.32

if [ "$MAIN" = 0 ] && ! dpkg -s libclang-dev >/dev/null 2>&1; then
    echo "setup: installing libclang-dev (needed by fmi-sys/bindgen)"
    SUDO=""
    if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq libclang-dev
fi

PY=${PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
    echo "setup: creating .venv with $($PY --version)"
    "$PY" -m venv .venv
fi
if ! .venv/bin/python -c "import fmpy, pytest, numpy, matplotlib, sys; sys.exit(fmpy.__version__ != '$FMPY_VERSION')" 2>/dev/null; then
    echo "setup: installing fmpy==$FMPY_VERSION, pytest, numpy, matplotlib into .venv"
    .venv/bin/python -m pip install --quiet --upgrade pip
    .venv/bin/python -m pip install --quiet "fmpy==$FMPY_VERSION" "pytest>=8,<9" "numpy>=1.26,<3" "matplotlib>=3.8,<4"
fi

if [ "$MAIN" = 1 ]; then exit 0; fi

# the project's Python tools (python/: hybeam-cosim, the co-simulation master; hybeam-sweep,
# parameter studies on Dask), editable, with their dependencies (dask, pandas, pyarrow, scipy,
# tomli-w, lxml) and the extras the tests need (test: pytest, pyvista, vtk; plot: matplotlib);
# ruff, which lints and formats them, and mypy, which type-checks them (python/pyproject.toml)
RUFF_VERSION=0.14.14
MYPY_VERSION=2.4.1
if ! .venv/bin/python -c "import hybeam.cosim.ssp, hybeam.sweep.sweep, dask.distributed, pyarrow, scipy, tomli_w, lxml, pyvista, vtk, matplotlib, pytest" 2>/dev/null ||
    ! .venv/bin/ruff --version 2>/dev/null | grep -q "$RUFF_VERSION" ||
    ! .venv/bin/mypy --version 2>/dev/null | grep -q "mypy $MYPY_VERSION " ||
    ! .venv/bin/hybeam-ssp --help >/dev/null 2>&1; then
    echo "setup: installing the Python tools (python/[test,plot], editable), ruff==$RUFF_VERSION and mypy==$MYPY_VERSION into .venv"
    .venv/bin/python -m pip install --quiet -e "python[test,plot]" "ruff==$RUFF_VERSION" "mypy==$MYPY_VERSION"
fi

# libcosim for the vehicle example's second host (examples/vehicle/cosim_libcosim.py); its
# wheels are CPython 3.11 manylinux_2_28: where none fits, its test says so and skips
LIBCOSIMPY_VERSION=0.0.6
if ! .venv/bin/python -c "import libcosimpy" 2>/dev/null; then
    echo "setup: installing libcosimpy==$LIBCOSIMPY_VERSION into .venv"
    .venv/bin/python -m pip install --quiet "libcosimpy==$LIBCOSIMPY_VERSION" ||
        echo "setup: libcosimpy==$LIBCOSIMPY_VERSION has no wheel for this Python; the libcosim run of examples/vehicle is skipped"
fi

# The views' browser test (scripts/test-view.sh): Debian's Chromium, Node.js and the viewer's
# npm packages (three.js, esbuild, playwright-core; versions locked in viewer/package-lock.json)
APT_VIEW=()
command -v chromium >/dev/null || APT_VIEW+=(chromium)
command -v npm >/dev/null || APT_VIEW+=(nodejs npm)
if [ ${#APT_VIEW[@]} -gt 0 ]; then
    echo "setup: installing ${APT_VIEW[*]} (the animation page's browser test)"
    SUDO=""
    if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${APT_VIEW[@]}"
fi
if ! cmp -s viewer/package-lock.json viewer/node_modules/.hybeam-lock 2>/dev/null; then
    echo "setup: npm ci in viewer/ (three.js, esbuild, playwright-core)"
    (cd viewer && npm ci --no-audit --no-fund --loglevel=error && cp package-lock.json node_modules/.hybeam-lock)
fi
