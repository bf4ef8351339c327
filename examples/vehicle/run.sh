#!/usr/bin/env bash
# The vehicle example: builds the car FMU (out/car.fmu) and the roof boom's beam FMU
# (out/boom.fmu, from scenes/boom.toml), couples them in fmpy over the bump and
# writes out/vehicle.csv and out/vehicle.png (examples/vehicle/README.md).
#   bash examples/vehicle/run.sh            the coupled run (Newton coupling, h = 1 ms)
#   bash examples/vehicle/run.sh --study    also the coupling study -> out/vehicle_study.md
#   bash examples/vehicle/run.sh --test     the example's pytest checks (run by scripts/test.sh)
set -euo pipefail
cd "$(dirname "$0")/../.."
[ -x .venv/bin/python ] || bash scripts/setup.sh
mkdir -p out
cargo build --release -p hybeam-vehicle --lib --bin car-fmu
target/release/car-fmu target/release/libhybeam_vehicle.so examples/vehicle/vehicle.toml out/car.fmu
boom=$(cargo fmu-build scenes/boom.toml --out out --platforms linux64 | tail -n 1)
case "${1:-}" in
    --test)
        .venv/bin/python -m pytest -q examples/vehicle/test_cosim.py --car out/car.fmu --boom "$boom"
        ;;
    --study)
        .venv/bin/python examples/vehicle/cosim.py out/car.fmu "$boom" --derivatives --out out/vehicle
        .venv/bin/python examples/vehicle/study.py out/car.fmu "$boom" --out out/vehicle_study.md
        ;;
    *)
        .venv/bin/python examples/vehicle/cosim.py out/car.fmu "$boom" --derivatives --out out/vehicle
        ;;
esac
