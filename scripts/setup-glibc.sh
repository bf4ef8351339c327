#!/usr/bin/env bash
# Installs the toolchain that links binaries/linux64 against glibc 2.31 (Ubuntu 20.04,
# Debian 11 and later can load the FMU; without it the .so needs the build machine's glibc,
# 2.34 on Debian 12): cargo-zigbuild and zig (the `ziglang` wheel) from PyPI, pinned, in a venv
# inside the project's target directory (cached with the build; ~440 MB). On demand: not part
# of scripts/setup.sh. fmu-build uses it when present. Idempotent. See docs/platforms.md.
set -euo pipefail
cd "$(dirname "$0")/.."

VENV=${CARGO_TARGET_DIR:-target}/zig/venv
if [ -x "$VENV/bin/cargo-zigbuild" ] && "$VENV/bin/python" -m ziglang version >/dev/null 2>&1; then
    exit 0
fi
echo "setup-glibc: installing cargo-zigbuild 0.24.0 and ziglang 0.17.1 into $VENV"
python3 -m venv "$VENV"
"$VENV/bin/pip" install -q cargo-zigbuild==0.24.0 ziglang==0.17.1
