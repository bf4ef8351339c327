#!/usr/bin/env bash
# An independent check of hybeam-realtime's per-step CPU time: the instructions of each step,
# counted by valgrind's callgrind, against the CPU time the harness measures natively.
#
#   bash benches/realtime/check_instructions.sh [FMU] [STEPS] [WARMUP] [NATIVE_RUNS]
#   (defaults: target/fmu/boom.fmu, packaged if missing; 2000 steps; 100 warm-up; 3 runs)
#   HARNESS_ARGS="--pin 1 --mlock" bash benches/realtime/check_instructions.sh   # native runs pinned
#
# Why callgrind: this machine has no hardware performance counters (`perf stat -e
# instructions:u true` says <not supported>), so perf_event_open cannot count instructions.
# Callgrind counts every executed instruction exactly and deterministically. The harness's step
# function `hybeam_realtime_step` (SetReal + DoStep + GetReal, not inlined, not mangled) is the
# only code collected (--collect-atstart=no --toggle-collect) and callgrind dumps after each
# call (--dump-after): dump k holds the instructions of step k-1, nothing of the harness's
# timers or input computation.
#
# What it prints: min, median, p99, p99.9, max and max/median of the instructions per step and of the
# native CPU time per step over the same steps (the FMU is deterministic: same inputs, same
# path), for NATIVE_RUNS native runs (their spread is the noise of the CPU-time ratio), the
# correlation of the two per step, and which steps are the slowest in each. Caveat: under
# valgrind the CPU reports fewer SIMD extensions (no AVX-512), so code that dispatches on CPU
# features at run time takes another path there than natively.
set -euo pipefail
export LC_ALL=C
cd "$(dirname "$0")/../.."

FMU=${1:-target/fmu/boom.fmu}
STEPS=${2:-2000}
WARMUP=${3:-100}
RUNS=${4:-3}
# options of the native runs (and the callgrind run), e.g. --pin 1 --mlock, --amplitude 5
read -r -a EXTRA <<<"${HARNESS_ARGS:-}"

command -v valgrind >/dev/null || { echo "valgrind is not installed (apt-get install valgrind)" >&2; exit 1; }
cargo build --release -q -p hybeam-realtime
HARNESS=target/release/hybeam-realtime
if [ ! -f "$FMU" ]; then
    if [ "$FMU" = target/fmu/boom.fmu ]; then
        cargo fmu-build scenes/boom.toml --out target/fmu --platforms linux64 | tail -1
    else
        echo "no FMU $FMU" >&2
        exit 1
    fi
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# 1. the native runs: per-step CPU time [µs], column 4 of the CSV
for r in $(seq 1 "$RUNS"); do
    "$HARNESS" "$FMU" --steps "$STEPS" --warmup "$WARMUP" "${EXTRA[@]}" --csv "$work/native$r.csv" >/dev/null
done

# 2. the same run under callgrind: instructions per step
echo "callgrind: $STEPS steps of $FMU (boom: about 20 ms a step under valgrind) ..." >&2
valgrind --tool=callgrind --collect-atstart=no --toggle-collect=hybeam_realtime_step \
    --dump-after=hybeam_realtime_step --callgrind-out-file="$work/cg.out" \
    "$HARNESS" "$FMU" --steps "$STEPS" --warmup "$WARMUP" "${EXTRA[@]}" >/dev/null 2>"$work/valgrind.log" || {
    tail -20 "$work/valgrind.log" >&2
    exit 1
}
# dump k (cg.out.k, k = 1..STEPS) is step k-1; the file without a part number is the empty
# dump at exit
for k in $(seq 1 "$STEPS"); do
    f="$work/cg.out.$k"
    [ -f "$f" ] || { echo "callgrind wrote no dump $k (of $STEPS)" >&2; exit 1; }
    printf '%d,%s\n' $((k - 1)) "$(sed -n 's/^summary: //p' "$f")"
    rm -f "$f"
done >"$work/instructions.csv"

# 3. the statistics over steps WARMUP..STEPS-1 (nearest-rank percentiles, as the harness)
stats() { # stdin: one value a line; prints min median p99 p99.9 max max/median
    sort -g | awk '{ v[NR] = $1 }
        function pct(p,   r) { r = p / 100 * NR; r = (r == int(r)) ? r : int(r) + 1; if (r < 1) r = 1; return v[r] }
        END { printf "%12.1f %12.1f %12.1f %12.1f %12.1f %10.3f", v[1], pct(50), pct(99), pct(99.9), v[NR], v[NR] / pct(50) }'
}
argmax() { # stdin: step,value; prints the step of the largest value
    sort -t, -k2 -g | tail -1 | cut -d, -f1
}
after_warmup() { awk -F, -v w="$WARMUP" '$1 >= w'; }

printf '\n%s: %s steps, statistics over steps %s..%s\n' "$FMU" "$STEPS" "$WARMUP" "$STEPS"
printf '%-28s %12s %12s %12s %12s %12s %10s %8s\n' "per step" min median p99 p99.9 max max/median "max at"
printf '%-28s %s %8s\n' "instructions (callgrind)" \
    "$(after_warmup <"$work/instructions.csv" | cut -d, -f2 | stats)" \
    "$(after_warmup <"$work/instructions.csv" | argmax)"
for r in $(seq 1 "$RUNS"); do
    tail -n +2 "$work/native$r.csv" | after_warmup | cut -d, -f1,4 >"$work/cpu$r.csv"
    printf '%-28s %s %8s\n' "CPU time [µs], native run $r" \
        "$(cut -d, -f2 <"$work/cpu$r.csv" | stats)" "$(argmax <"$work/cpu$r.csv")"
done

# the correlation per step of instructions and native CPU time (run 1), and where each run's
# slowest step stands in the instruction counts
join -t, <(after_warmup <"$work/instructions.csv" | sort -t, -k1,1) \
    <(sort -t, -k1,1 "$work/cpu1.csv") >"$work/joined.csv"
awk -F, '{ n++; x += $2; y += $3; xx += $2 * $2; yy += $3 * $3; xy += $2 * $3 }
    END { c = (n * xy - x * y) / sqrt((n * xx - x * x) * (n * yy - y * y));
          printf "\ncorrelation per step of instructions and native CPU time (run 1): %.3f\n", c }' \
    "$work/joined.csv"
imed=$(after_warmup <"$work/instructions.csv" | cut -d, -f2 | sort -g | awk '{ v[NR] = $1 } END { r = 0.5 * NR; r = (r == int(r)) ? r : int(r) + 1; print v[r] }')
cmed=$(cut -d, -f2 <"$work/cpu1.csv" | sort -g | awk '{ v[NR] = $1 } END { r = 0.5 * NR; r = (r == int(r)) ? r : int(r) + 1; print v[r] }')
awk -v i="$imed" -v c="$cmed" 'BEGIN { printf "median instructions per native CPU ns (run 1): %.2f (the callgrind count; see the caveat above)\n", i / (c * 1e3) }'
for r in $(seq 1 "$RUNS"); do
    s=$(argmax <"$work/cpu$r.csv")
    i=$(awk -F, -v s="$s" '$1 == s { print $2 }' "$work/instructions.csv")
    awk -v r="$r" -v s="$s" -v i="$i" -v m="$imed" \
        'BEGIN { printf "native run %s: its slowest step %s executes %.3f x the median instructions\n", r, s, i / m }'
done
