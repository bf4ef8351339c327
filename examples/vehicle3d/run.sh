#!/usr/bin/env bash
# The spatial vehicle example: builds the four-wheel car FMU (out/car3d.fmu) and the roof
# boom's spatial beam FMU (out/boom_3d.fmu, from scenes/boom_3d.toml), couples them with
# hybeam-cosim over the bump under the left wheels (examples/vehicle3d/system.toml) and writes
# out/vehicle3d/cosim.csv and out/vehicle3d/cosim.png, the boom's ParaView series
# (out/vehicle3d/view/) and the animation out/vehicle3d/animation.html
# (examples/vehicle3d/README.md).
#   bash examples/vehicle3d/run.sh          the coupled run (implicit coupling, h = 1 ms)
#   bash examples/vehicle3d/run.sh --test   the example's pytest checks (test_cosim3d.py; the
#                                           symmetric case compares with the planar system:
#                                           out/car.fmu and the planar boom, both modal bodies
#                                           geometrically nonlinear)
set -euo pipefail
cd "$(dirname "$0")/../.."
[ -x .venv/bin/hybeam-cosim ] || bash scripts/setup.sh
mkdir -p out
cargo build --release -p hybeam-vehicle3d --lib --bin car3d-fmu --features export
target/release/car3d-fmu target/release/libhybeam_vehicle3d.so examples/vehicle3d/vehicle3d.toml out/car3d.fmu
boom=$(cargo fmu-build scenes/boom_3d.toml --out out --platforms linux64 | tail -n 1)
SYSTEM=examples/vehicle3d/system.toml
case "${1:-}" in
    --test)
        # the planar pair of the symmetric comparison (as examples/vehicle/run.sh builds it)
        cargo build --release -p hybeam-vehicle --lib --bin car-fmu --features export
        target/release/car-fmu target/release/libhybeam_vehicle.so examples/vehicle/vehicle.toml out/car.fmu
        # its modal segment nonlinear, as the spatial modal body of boom_3d: the comparison is
        # then one model in two codes
        mkdir -p out/vehicle3d/planar
        planar_boom=$(cargo fmu-build scenes/boom.toml --out out/vehicle3d/planar \
            --platforms linux64 | tail -n 1)
        .venv/bin/python -m pytest -q examples/vehicle3d/test_cosim3d.py --car out/car3d.fmu \
            --boom "$boom" --planar-car out/car.fmu --planar-boom "$planar_boom"
        ;;
    *)
        # the same system as SSP 1.0 (examples/vehicle3d/system.ssd with the FMUs packed into
        # resources/): hybeam-cosim out/vehicle3d/vehicle3d.ssp runs it as system.toml (docs/coupling.md)
        .venv/bin/hybeam-ssp "$SYSTEM" --out out/vehicle3d/vehicle3d.ssp --fmu car=out/car3d.fmu --fmu boom="$boom"
        # the boom FMU writes its shape into out/vehicle3d/view; the page shows the car body
        # (4.1 x 1.8 x 1.3 m) as a box carried by the mount frame (the roof point 0.3 m ahead
        # of and 0.9 m above the centre of mass)
        rm -rf out/vehicle3d/view
        .venv/bin/hybeam-cosim "$SYSTEM" --scheme implicit --step 1e-3 --out out/vehicle3d \
            --set boom.visualization.directory=out/vehicle3d/view
        cargo run --release --quiet --bin hybeam -- animate out/vehicle3d/view \
            --body 4.1,1.8,1.3 --body-centre -0.45,0,-0.65 --title "car over a one-sided bump with the roof boom" \
            --out out/vehicle3d/animation.html
        ;;
esac
