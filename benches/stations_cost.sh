#!/usr/bin/env bash
# What the loads output costs per communication step (issue 40): the FMU of
# scenes/sprayer_boom.toml with 4 stations (its 3 and one at the end piece's joint) and
# `outputs.stress` against the same scene without them,
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
# the equipped scene: the shipped one and a fourth station at the end piece's joint
cp scenes/sprayer_boom.toml "$work/sprayer_boom.toml"
printf '\n[[stations]]\nname = "tip_joint"\nsegment = "tip"\nat = 0.0\n' >>"$work/sprayer_boom.toml"
cargo build --release -q -p hybeam-realtime
with=$(cargo fmu-build "$work/sprayer_boom.toml" --out "$work" --platforms linux64 | tail -n 1)
bare=$(cargo fmu-build "$work/sprayer_bare.toml" --out "$work" --platforms linux64 | tail -n 1)
count() { # FMU: instructions of STEPS steps (SetReal + DoStep + GetReal)
    valgrind --tool=callgrind --collect-atstart=no --toggle-collect=hybeam_realtime_step \
        --callgrind-out-file=/dev/null target/release/hybeam-realtime "$1" --steps "$STEPS" \
        --warmup 0 --amplitude 1 2>&1 >/dev/null | grep -o 'Collected : [0-9]*' | grep -o '[0-9]*$'
}
a=$(count "$bare")
b=$(count "$with")
echo "| FMU step (1 ms, $STEPS steps) | without [instructions/step] | 4 stations + outputs.stress | extra |"
echo "|---|---|---|---|"
awk -v n="$STEPS" -v a="$a" -v b="$b" \
    'BEGIN { printf "| sprayer_boom | %.4g | %.4g | %+.1f %% |\n", a / n, b / n, 100 * b / a - 100 }'
