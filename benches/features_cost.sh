#!/usr/bin/env bash
# What the boom's equipment costs per step (issue 39): scenes/sprayer_boom.toml (4 attached
# masses, a tapered ANCF arm, a line load, a bent end piece) against the same arm bare (no
# masses, no line load, the arm at its mean section, the end piece straight), 0.5 s of steps,
# instructions counted by callgrind (deterministic; valgrind required), at the scene's Newton
# tolerance and at a looser one where both take the same Newton iterations.
#   bash benches/features_cost.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --bin hybeam -q
bare=(--set "masses=[]" --set "segments.1.line_load=[0.0,0.0]" --set segments.1.diameter=0.045
      --set segments.1.inner_diameter=0.0395 --set segments.2.initial_curvature=0.0)
run() { # tolerance, extra args: prints "instructions iterations steps"
    local tol=$1; shift
    local out
    out=$(valgrind --tool=callgrind --callgrind-out-file=/dev/null target/release/hybeam run \
        scenes/sprayer_boom.toml --out /dev/null --set "solver.tolerance=$tol" "$@" 2>&1)
    local ins iters steps
    ins=$(grep -o 'Collected : [0-9]*' <<<"$out" | grep -o '[0-9]*$')
    iters=$(grep -o '[0-9]* Newton iterations' <<<"$out" | grep -o '^[0-9]*')
    steps=$(grep -o '[0-9]* steps' <<<"$out" | grep -o '^[0-9]*')
    echo "$ins $iters $steps"
}
echo "| tolerance | scene | instructions / step | Newton iterations / step | instructions / iteration |"
echo "|---|---|---|---|---|"
for tol in 1e-11 1e-9; do
    read -r wi wn ws < <(run "$tol")
    read -r bi bn bs < <(run "$tol" "${bare[@]}")
    awk -v t="$tol" -v wi="$wi" -v wn="$wn" -v ws="$ws" -v bi="$bi" -v bn="$bn" -v bs="$bs" 'BEGIN {
        printf "| %s | bare | %.0f | %.3f | %.0f |\n", t, bi/bs, bn/bs, bi/bn
        printf "| %s | equipped | %.0f (%+.1f %%) | %.3f (%+.1f %%) | %.0f (%+.1f %%) |\n", t,
            wi/ws, 100*(wi/ws)/(bi/bs)-100, wn/ws, 100*(wn/ws)/(bn/bs)-100, wi/wn, 100*(wi/wn)/(bi/bn)-100
    }'
done
