#!/usr/bin/env bash
# Installs the win64 cross toolchain on demand (Debian 12; root or sudo). Not part of
# scripts/setup.sh: users who only want binaries/linux64 do not need it.
#   - rustc-web/cargo-web/rust-web-src 1.96 (Debian's /usr/bin/cargo with the std sources, so
#     `-Zbuild-std` can build std for x86_64-pc-windows-gnu; rustup's toolchain stays the
#     default for the linux64 build)
#   - gcc-mingw-w64-x86-64 (linker, strip, the C test host)
#   - wine64, wine (run the C test host; tests only), unzip (unpacks the FMU in the test)
# Idempotent: does nothing when everything is there. See docs/platforms.md.
set -euo pipefail

PKGS=(rustc-web cargo-web rust-web-src gcc-mingw-w64-x86-64 binutils-mingw-w64-x86-64 wine64 wine unzip)
missing=()
for p in "${PKGS[@]}"; do
    dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
    exit 0
fi
echo "setup-win64: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
