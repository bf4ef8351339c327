#!/usr/bin/env bash
# What the loads output costs per communication step (issue 40): the FMU of
# scenes/sprayer_boom.toml with 4 stations (its 3 and a fourth at the end piece's joint, or
# inside the modal root segment) and `outputs.stress` against the same scene without them,
# each driven by the native host (benches/realtime: fmi2SetReal of a tip-force sine, fmi2DoStep
# of 1 ms, fmi2GetReal of every output) for STEPS steps, the instructions of those calls alone
# counted by callgrind (--toggle-collect on the harness's step function; valgrind required).
#   bash benches/stations_cost.sh [STEPS]     (default 500)
set -euo pipefail
cd "$(dirname "$0")/.."
STEPS=${1:-500}
command -v valgrind >/dev/null || { echo "valgrind is not installed (apt-get install valgrind)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# the bare scene: the same arm without its [[stations]] tables and with outputs.stress = false
python3 - "$work/sprayer_bare.toml" <<'EOF'
import re, sys
s = open("scenes/sprayer_boom.toml").read()
s = re.sub(r"\[\[stations\]\]\n(?:[^\[\n][^\n]*\n|\n)*", "", s)
s = s.replace("stress = true", "stress = false").replace('name = "sprayer_boom"', 'name = "sprayer_bare"')
assert "[[stations]]" not in s and "stress = false" in s
open(sys.argv[1], "w").write(s)
EOF
# the equipped scenes: the shipped one and a fourth station at the end piece's joint (a node)
# or inside the modal root segment (its part [0, 0.5 m] integrated at each output)
mkdir -p "$work/joint" "$work/modal"
cp scenes/sprayer_boom.toml "$work/joint/sprayer_boom.toml"
printf '\n[[stations]]\nname = "tip_joint"\nsegment = "tip"\nat = 0.0\n' >>"$work/joint/sprayer_boom.toml"
cp scenes/sprayer_boom.toml "$work/modal/sprayer_boom.toml"
printf '\n[[stations]]\nname = "root_mid"\nsegment = "root"\nat = 0.5\n' >>"$work/modal/sprayer_boom.toml"
cargo build --release -q -p hybeam-realtime
joint=$(cargo fmu-build "$work/joint/sprayer_boom.toml" --out "$work/joint" --platforms linux64 | tail -n 1)
modal=$(cargo fmu-build "$work/modal/sprayer_boom.toml" --out "$work/modal" --platforms linux64 | tail -n 1)
bare=$(cargo fmu-build "$work/sprayer_bare.toml" --out "$work" --platforms linux64 | tail -n 1)
count() { # FMU: instructions of STEPS steps (SetReal + DoStep + GetReal)
    valgrind --tool=callgrind --collect-atstart=no --toggle-collect=hybeam_realtime_step \
        --callgrind-out-file=/dev/null target/release/hybeam-realtime "$1" --steps "$STEPS" \
        --warmup 0 --amplitude 1 2>&1 >/dev/null | grep -o 'Collected : [0-9]*' | grep -o '[0-9]*$'
}
a=$(count "$bare")
b=$(count "$joint")
c=$(count "$modal")
echo "| sprayer_boom FMU, 1 ms steps ($STEPS) | instructions per step | extra |"
echo "|---|--:|--:|"
awk -v n="$STEPS" -v a="$a" -v b="$b" -v c="$c" 'BEGIN {
    printf "| without stations, outputs.stress = false | %.4g | |\n", a / n
    printf "| 4 stations (3 + the end piece joint) + outputs.stress | %.4g | %+.1f %% |\n", b / n, 100 * b / a - 100
    printf "| 4 stations (3 + inside the modal root) + outputs.stress | %.4g | %+.1f %% |\n", c / n, 100 * c / a - 100
}'
