#!/usr/bin/env bash
# Peer comparison of hybeam with Exudyn 1.13.6 (issue 23); see benches/peers/README.md.
#   bash benches/peers/run.sh            # full grid: docs/report/peers_*, docs/performance.md
#   bash benches/peers/run.sh --quick    # smoke check, a few minutes: target/peers-quick/
#   bash benches/peers/run.sh --problems large   # large deformation: docs/peers-large.md
# Builds hybeam (release) and creates the venv with Exudyn if missing; further arguments go to
# peers.py (--problems planar, --t-end 0.5, --repeats 1, --shared "note", ...).
set -euo pipefail
cd "$(dirname "$0")/../.."
target="${CARGO_TARGET_DIR:-target}"
venv="$target/peers-venv"
python="${PYTHON:-python3}"

cargo build --release --bin hybeam

if ! "$venv/bin/python" -c 'import exudyn, numpy, matplotlib' 2>/dev/null; then
    # The Exudyn 1.13.6 wheels on PyPI are per CPython version (tested: 3.11, linux x86_64).
    "$python" -m venv "$venv"
    "$venv/bin/pip" install --quiet exudyn==1.13.6 numpy==2.4.6 matplotlib==3.11.2
fi

export PEERS_COMMAND="bash benches/peers/run.sh$(printf ' %q' "$@")"
exec "$venv/bin/python" benches/peers/peers.py --hybeam "$target/release/hybeam" "$@"
