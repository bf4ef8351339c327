#!/usr/bin/env bash
# Packages the shipped real-time-relevant scenes and measures each FMU's per-step time with
# hybeam-realtime; prints the Markdown table of docs/realtime.md ("Harness").
#
#   bash benches/realtime/run.sh [harness options]      e.g. --steps 100000 --pin 1 --mlock
#   SCENES="boom case1" bash benches/realtime/run.sh     only these scenes
#
# Each scene is driven with a tip force sine of 2 Hz whose amplitude suits the beam (a tenth of
# the roof boom's weight, about the weight of the thin rods and strip): the figures depend on
# the load only through the Newton iterations it costs. Mounted scenes (boom, boom_3d) also heave
# their mount 10 mm at 1 Hz (the harness's defaults). Options given here are passed to every run
# after these (a later --amplitude wins).
set -euo pipefail
cd "$(dirname "$0")/../.."

SCENES=${SCENES:-"boom boom_3d boom_rt boom_3d_rt case1 case1_3d strip_3d"}
amplitude() { # tip force amplitude [N] for a scene
    case "$1" in
        boom | boom_3d | boom_rt | boom_3d_rt) echo 10 ;; # 10.4 kg tube boom: weight ~100 N
        case1 | case1_3d) echo 0.01 ;; # 2 mm rod, 9.9 g: weight ~0.1 N
        strip_3d) echo 0.002 ;;      # 4 mm x 0.5 mm strip, 6.3 g, very soft
        *) echo 1 ;;
    esac
}

cargo build --release -q -p hybeam-realtime
rows=()
for id in $SCENES; do
    fmu=$(cargo fmu-build "scenes/$id.toml" --out target/fmu --platforms linux64 2>/dev/null | tail -1)
    [ -f "$fmu" ] || { echo "packaging scenes/$id.toml did not give an FMU (got '$fmu')" >&2; exit 1; }
    echo "measuring $fmu ..." >&2
    rows+=("$(target/release/hybeam-realtime "$fmu" --amplitude "$(amplitude "$id")" --markdown "$@")")
done
target/release/hybeam-realtime --markdown-header
printf '%s\n' "${rows[@]}"
