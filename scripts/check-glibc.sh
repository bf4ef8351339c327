#!/usr/bin/env bash
# Fails unless the linux64 binary of each FMU given needs no glibc symbol version newer than
# MAX (default 2.31) and exports exactly the 34 fmi2 functions. Usage: check-glibc.sh A.fmu ...
set -euo pipefail
MAX=${GLIBC_MAX:-2.31}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
status=0
for fmu in "$@"; do
    id=$(basename "$fmu" .fmu)
    unzip -p "$fmu" "binaries/linux64/$id.so" >"$tmp/$id.so"
    newest=$(objdump -T "$tmp/$id.so" | grep -o 'GLIBC_[0-9.]*' | sed 's/GLIBC_//' | sort -V | tail -n 1)
    exports=$(nm -D --defined-only "$tmp/$id.so" | awk '{print $3}')
    n_fmi=$(echo "$exports" | grep -c '^fmi2' || true)
    n_other=$(echo "$exports" | grep -vc '^fmi2' || true)
    if [ "$(printf '%s\n%s\n' "$newest" "$MAX" | sort -V | tail -n 1)" != "$MAX" ]; then
        echo "check-glibc: $fmu needs GLIBC_$newest (> $MAX)"
        status=1
    elif [ "$n_fmi" != 34 ] || [ "$n_other" != 0 ]; then
        echo "check-glibc: $fmu exports $n_fmi fmi2 functions and $n_other other symbols (want 34, 0)"
        status=1
    else
        echo "check-glibc: $fmu: newest glibc symbol GLIBC_$newest (<= $MAX), 34 exports"
    fi
done
exit $status
