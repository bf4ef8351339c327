#!/usr/bin/env bash
# The vehicle example: builds the car FMU (out/car.fmu) and the roof boom's beam FMU
# (out/boom.fmu, from scenes/boom.toml), couples them with hybeam-cosim over the bump
# (examples/vehicle/system.toml) and writes out/vehicle/cosim.csv and out/vehicle/cosim.png, the
# boom's ParaView series (out/vehicle/view/) and the animation out/vehicle/animation.html
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
        # the same system as SSP 1.0 (examples/vehicle/system.ssd with the FMUs packed into
        # resources/): hybeam-cosim out/vehicle/vehicle.ssp runs it as system.toml (docs/coupling.md)
        .venv/bin/hybeam-ssp "$SYSTEM" --out out/vehicle/vehicle.ssp --fmu car=out/car.fmu --fmu boom="$boom"
        # the boom FMU writes its shape (ParaView series) into out/vehicle/view; the page of
        # the run then shows the car body as a box carried by the mount frame (the roof point
        # 0.3 m ahead of and 0.9 m above the centre of mass; a 4.1 x 1.3 x 1.8 m body)
        rm -rf out/vehicle/view
        .venv/bin/hybeam-cosim "$SYSTEM" --scheme implicit --step 1e-3 --out out/vehicle \
            --set boom.visualization.directory=out/vehicle/view
        # the root weld's fatigue over the pass (EN 1993-1-9 detail category 71, m = 3:
        # C = 2e6 * 71e6^3; docs/fatigue.md)
        .venv/bin/hybeam-fatigue out/vehicle/cosim.csv --station root_weld \
            --column boom.station.root_weld.stress --sn m=3,C=7.16e29 \
            --json out/vehicle/root_weld_fatigue.json --plot out/vehicle/root_weld_cycles.png
        cargo run --release --quiet --bin hybeam -- animate out/vehicle/view \
            --body 4.1,1.3,1.8 --body-centre -0.45,-0.65,0 --title "car over a bump with the roof boom" \
            --out out/vehicle/animation.html
        ;;
esac
