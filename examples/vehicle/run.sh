#!/usr/bin/env bash
# The vehicle example: builds the car FMU (out/car.fmu) and the roof boom's beam FMU
# (out/boom.fmu, from scenes/boom.toml), couples them with hybeam-cosim over the bump
# (examples/vehicle/system.toml) and writes out/vehicle/cosim.csv and out/vehicle/cosim.png
# (examples/vehicle/README.md).
#   bash examples/vehicle/run.sh            the coupled run (implicit coupling, h = 1 ms)
#   bash examples/vehicle/run.sh --study    the stability map and the order study of
#                                           docs/coupling.md (docs/report/coupling_*)
#   bash examples/vehicle/run.sh --test     the example's pytest checks (run by scripts/test.sh)
set -euo pipefail
cd "$(dirname "$0")/../.."
[ -x .venv/bin/hybeam-cosim ] || bash scripts/setup.sh
mkdir -p out
cargo build --release -p hybeam-vehicle --lib --bin car-fmu --features export
target/release/car-fmu target/release/libhybeam_vehicle.so examples/vehicle/vehicle.toml out/car.fmu
boom=$(cargo fmu-build scenes/boom.toml --out out --platforms linux64 | tail -n 1)
SYSTEM=examples/vehicle/system.toml
case "${1:-}" in
    --test)
        .venv/bin/python -m pytest -q examples/vehicle/test_cosim.py --car out/car.fmu --boom "$boom"
        ;;
    --study)
        .venv/bin/hybeam-cosim-study map "$SYSTEM" --scheme naive --scheme implicit \
            --scheme interface --steps 1e-4,2.5e-4,5e-4,1e-3,2e-3,5e-3,1e-2,2e-2 \
            --grid boom.mass_factor=1,10,20,50,100 --t-end 2 --out docs/report/coupling_map
        .venv/bin/hybeam-cosim-study map "$SYSTEM" --scheme partner \
            --steps 1e-4,2.5e-4,5e-4,1e-3,2e-3,5e-3,1e-2,2e-2 \
            --grid boom.mass_factor=1,10,20,50,100 --t-end 2 --out docs/report/coupling_map_partner
        .venv/bin/hybeam-cosim-study order "$SYSTEM" --scheme implicit \
            --steps 2e-2,1e-2,5e-3,2e-3,1e-3,5e-4 --reference 1e-4 --t-end 2 \
            --columns car.body.pitch,boom.tip.position.y --out docs/report/coupling_order
        ;;
    *)
        .venv/bin/hybeam-cosim "$SYSTEM" --scheme implicit --step 1e-3 --out out/vehicle
        ;;
esac
