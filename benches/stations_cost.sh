#!/usr/bin/env bash
# What the loads output costs (issue 40): scenes/sprayer_boom.toml with its three stations and
# `outputs.stress` against the same scene without them (--set stations=[] --set
# outputs.stress=false), 0.5 s, outputs every 1 ms (the FMU's usual communication step) and every
# internal step (0.2 ms: the worst case, a host stepping at the internal step), instructions
# counted by callgrind (valgrind required).
#   bash benches/stations_cost.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --bin hybeam -q
run() { # output step, extra args: prints the instruction count
    valgrind --tool=callgrind --callgrind-out-file=/dev/null target/release/hybeam run \
        scenes/sprayer_boom.toml --out /dev/null --quiet --output-step "$1" "${@:2}" 2>&1 |
        grep -o 'Collected : [0-9]*' | grep -o '[0-9]*$'
}
echo "| output step [s] | without [instructions] | 3 stations + outputs.stress | extra |"
echo "|---|---|---|---|"
for h in 1e-3 2e-4; do
    without=$(run "$h" --set "stations=[]" --set outputs.stress=false)
    with=$(run "$h")
    awk -v h="$h" -v a="$without" -v b="$with" \
        'BEGIN { printf "| %s | %.4g | %.4g | %+.1f %% |\n", h, a, b, 100 * b / a - 100 }'
done
