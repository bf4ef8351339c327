#!/usr/bin/env bash
# The sweep example (docs/sweeps.md): builds the roof boom's FMU (out/boom.fmu) and runs
# examples/sweeps/boom.toml on a Dask LocalCluster into out/sweeps/boom/ (variants.parquet,
# series.parquet, sweep.png); a rerun skips the variants already there.
#   bash examples/sweeps/run.sh           the example study
#   bash examples/sweeps/run.sh --test    the sweep tests (run by scripts/test.sh)
set -euo pipefail
cd "$(dirname "$0")/../.."
[ -x .venv/bin/hybeam-sweep ] || bash scripts/setup.sh
cargo fmu-build scenes/boom.toml --out out --platforms linux64 >/dev/null
if [ "${1:-}" = --test ]; then
    .venv/bin/python -m pytest -q -p no:logging examples/sweeps/test_sweep.py --boom out/boom.fmu
else
    .venv/bin/hybeam-sweep run examples/sweeps/boom.toml --out out/sweeps/boom "$@"
fi
