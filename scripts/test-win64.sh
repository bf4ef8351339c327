#!/usr/bin/env bash
# The win64 FMU test (docs/platforms.md). For each scene below: package a two-platform FMU
# (`fmu-build --platforms linux64,win64`), unpack it, run the C host
# crates/fmu/tests/win64/host.c built with mingw-w64 under Wine on binaries/win64/<id>.dll and
# built with gcc natively on binaries/linux64/<id>.so (the same FMI call sequence), and compare
# the two output histories. The gate is strict: every output within 1e-12 * max(1, |value|)
# (measured: bit-identical, 50 of 50 rows on each scene), because the engine takes its
# transcendental functions from the `libm` crate (src/math.rs), not from the platform's C
# library (glibc vs msvcrt). For information the linux64 binary also runs with glibc's math
# functions replaced by the `libm` crate's (LD_PRELOAD, crates/fmu/tests/win64/libm-shim) and
# that spread is printed; WIN64_STRICT=0 makes it the gate instead (10x for tip.*, 100x others).
# A Wine run fails on a non-zero exit code, a missing "HOST: OK", or any "Unhandled" exception
# in Wine's output (a thread crashing after FreeLibrary does not change the exit code).
# Also checked: the DLL exports exactly the 34 fmi2 functions and no test-only file is in the
# FMU; `fmpy validate` on the FMU when the .venv exists; `fmutool -check` (its own venv in target/).
# Installs the toolchain on demand (scripts/setup-win64.sh). Ends with "win64: N passed, M failed".
set -euo pipefail
cd "$(dirname "$0")/.."

# The scenes tested; adding one is one word here (or WIN64_SCENES="..." overrides the list).
SCENES=${WIN64_SCENES:-"scenes/case1.toml scenes/case3.toml scenes/case1_3d.toml"}

bash scripts/setup-win64.sh
# fmutool 1.7.4.1 (PyPI, pulls PyQt5) in its own venv inside target/, created on first use
FMUTOOL_VENV=${CARGO_TARGET_DIR:-target}/fmutool/venv
FMUTOOL=$FMUTOOL_VENV/bin/fmutool
if [ ! -x "$FMUTOOL" ]; then
    python3 -m venv "$FMUTOOL_VENV"
    "$FMUTOOL_VENV/bin/pip" install -q fmutool==1.7.4.1
fi
if [ "${WIN64_STRICT:-1}" = 0 ]; then unset WIN64_STRICT; else export WIN64_STRICT=1; fi
OUT=target/win64-test
BIN=$OUT/bin
mkdir -p "$BIN"
# A Wine prefix of its own (about 3 s to create on first use; not inside target/, which CI caches).
export WINEPREFIX=${HYBEAM_WINEPREFIX:-${XDG_CACHE_HOME:-$HOME/.cache}/hybeam/wine64}
export WINEDEBUG=-all
unset DISPLAY
PY=${PYTHON_VENV:-.venv}/bin/python

t0=$(date +%s)
echo "== win64: building the C host (mingw-w64 and gcc) and the test-only bcryptprimitives shim"
SRC=crates/fmu/tests/win64
x86_64-w64-mingw32-gcc -O2 -Wall -Wextra -Werror -D__USE_MINGW_ANSI_STDIO=1 \
    -o "$BIN/host.exe" "$SRC/host.c"
gcc -O2 -Wall -Wextra -Werror -o "$BIN/host" "$SRC/host.c" -ldl -lm
x86_64-w64-mingw32-gcc -O2 -Wall -Werror -shared -o "$BIN/bcryptprimitives.dll" \
    "$SRC/bcryptprimitives.c" -ladvapi32 -Wl,--kill-at
nice -n 19 cargo build -q --release --manifest-path "$SRC/libm-shim/Cargo.toml" \
    --target-dir "$OUT/libm-shim"
LIBM_SHIM=$(realpath "$OUT/libm-shim/release/libhybeam_libm_shim.so")
if [ ! -f "$WINEPREFIX/system.reg" ]; then
    echo "== win64: creating the Wine prefix $WINEPREFIX"
    mkdir -p "$WINEPREFIX"
    wineboot -i >"$OUT/wineboot.log" 2>&1 || true
    wineserver -w
fi
# Wine 8 lacks bcryptprimitives.dll, which Rust's std imports (ProcessPrng); Windows 10/11 have it.
cp "$BIN/bcryptprimitives.dll" "$WINEPREFIX/drive_c/windows/system32/"

# The exported names of a DLL (its export directory), sorted.
exports() {
    x86_64-w64-mingw32-objdump -p "$1" |
        awk '/\[Ordinal\/Name Pointer\] Table/ {on = 1; next} on && /^[ \t]*\[/ {print $NF; next} on {on = 0}' |
        sort
}
# Exactly the 34 functions the libloading host loads (no dependency symbol: crates/fmi2/src/sys.rs).
WANT_EXPORTS=$(grep -o 'b"fmi2[A-Za-z]*"' crates/fmu/tests/host/mod.rs | sed 's/^b"//; s/"$//' | sort)

passed=0
failed=0
# No dependency may bring a thread pool into the DLL (faer's default `rayon` feature does, through
# spindle; its threads crash after FreeLibrary). A pool may start only for large problems, which
# the run-time thread count below would not see, so the tree is checked too.
pools=$(cargo tree -q -p hybeam-fmu -e normal --target x86_64-pc-windows-gnu --prefix none |
    grep -Ei '^(rayon|rayon-core|spindle|crossbeam[a-z-]*|threadpool|tokio|async-std) ' | sort -u || true)
if [ -n "$pools" ]; then
    echo "FAIL the win64 dependency tree has thread pools: $pools"
    failed=$((failed + 1))
else
    echo "dependency tree of hybeam-fmu for x86_64-pc-windows-gnu: no rayon/spindle/crossbeam/thread pool"
fi
fail() {
    echo "FAIL $1"
    failed=$((failed + 1))
}
first=1
for scene in $SCENES; do
    id=$(basename "$scene" .toml)
    echo "== win64: $scene"
    fmu=$(nice -n 19 cargo fmu-build "$scene" --platforms linux64,win64 --out "$OUT/fmu" | tail -n 1)
    dir=$OUT/unpacked/$id
    rm -rf "$dir"
    mkdir -p "$dir"
    unzip -q "$fmu" -d "$dir"
    ok=1
    entries=$(unzip -Z1 "$fmu" | tr '\n' ' ')
    want="modelDescription.xml binaries/linux64/$id.so binaries/win64/$id.dll resources/scene.toml "
    [ "$entries" = "$want" ] || { echo "FMU entries: $entries (want $want)"; ok=0; }
    dll=$dir/binaries/win64/$id.dll
    got=$(exports "$dll")
    if [ "$got" != "$WANT_EXPORTS" ] || [ "$(echo "$got" | wc -l)" != 34 ]; then
        echo "DLL exports differ from the 34 fmi2 functions:"
        diff <(echo "$WANT_EXPORTS") <(echo "$got") || true
        ok=0
    fi
    echo "DLL imports: $(x86_64-w64-mingw32-objdump -p "$dll" | awk '/DLL Name:/ {print $3}' | tr '\n' ' ')"
    if [ -x "$PY" ]; then
        if ! "$PY" -m fmpy validate "$fmu" >"$OUT/$id.validate.txt" 2>&1; then
            cat "$OUT/$id.validate.txt"
            ok=0
        else
            echo "fmpy validate: $(tail -n 1 "$OUT/$id.validate.txt")"
        fi
    fi
    # fmutool (fmu-manipulation-toolbox) generic conformity check of the two-platform FMU
    if ! "$FMUTOOL" -input "$fmu" -check >"$OUT/$id.fmutool.txt" 2>&1 ||
        ! grep -q "compliant with FMI-2.0" "$OUT/$id.fmutool.txt" || grep -q "ERROR" "$OUT/$id.fmutool.txt"; then
        cat "$OUT/$id.fmutool.txt"
        ok=0
    else
        echo "fmutool -check: $(grep compliant "$OUT/$id.fmutool.txt")"
    fi

    "$BIN/host" "$(realpath "$dir")" "$OUT/$id.linux64.csv" >"$OUT/$id.linux64.out" 2>&1 ||
        { cat "$OUT/$id.linux64.out"; ok=0; }
    LD_PRELOAD=$LIBM_SHIM "$BIN/host" "$(realpath "$dir")" "$OUT/$id.linux64-libm.csv" \
        >"$OUT/$id.linux64-libm.out" 2>&1 || { cat "$OUT/$id.linux64-libm.out"; ok=0; }
    # Under Wine the FMU folder is Z:\<unix path>; the first scene is also copied to C:\hybeam
    # and run from there (resource URI file:///C:/hybeam/<id>/resources), which must give the
    # same history.
    runs=("Z:$(realpath "$dir" | tr / '\\')")
    if [ $first = 1 ]; then
        rm -rf "$WINEPREFIX/drive_c/hybeam/$id"
        mkdir -p "$WINEPREFIX/drive_c/hybeam"
        cp -r "$dir" "$WINEPREFIX/drive_c/hybeam/$id"
        runs+=("C:\\hybeam\\$id")
    fi
    for win_dir in "${runs[@]}"; do
        tag=${win_dir%%:*}
        csv=$OUT/$id.win64-$tag.csv
        log=$OUT/$id.win64-$tag.out
        rm -f "$csv"
        start=$EPOCHREALTIME
        rc=0
        wine "$BIN/host.exe" "$win_dir" "Z:$(realpath "$OUT" | tr / '\\')\\$(basename "$csv")" \
            >"$log" 2>&1 || rc=$?
        secs=$(awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN {printf "%.1f", b - a}')
        grep -v 'wine32 is missing\|multiarch needs to be enabled\|dpkg --add-architecture\|apt-get install wine32' "$log" || true
        echo "wine run ($tag: form): exit $rc, ${secs} s"
        if [ $rc != 0 ] || ! grep -q '^HOST: OK' "$log" || grep -q 'Unhandled' "$log"; then
            echo "wine run failed (exit $rc; HOST: OK missing or an Unhandled exception)"
            ok=0
        fi
        "$BIN/host" --compare "$csv" "$OUT/$id.linux64.csv" "$OUT/$id.linux64-libm.csv" || ok=0
    done
    if [ $first = 1 ] && ! cmp -s "$OUT/$id.win64-Z.csv" "$OUT/$id.win64-C.csv"; then
        echo "the C: and Z: runs differ"
        ok=0
    fi
    first=0
    if [ $ok = 1 ]; then passed=$((passed + 1)); else fail "$scene"; fi
done
wineserver -k 2>/dev/null || true
echo "win64 test took $(($(date +%s) - t0)) s"
echo "win64: $passed passed, $failed failed"
[ "$failed" = 0 ]
