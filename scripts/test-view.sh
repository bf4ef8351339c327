#!/usr/bin/env bash
# The views' end-to-end test: the committed viewer bundle is what viewer/package-lock.json
# builds, and the animation pages of a planar and a spatial run work in headless Chromium
# (viewer/test/page.test.mjs). Needs what scripts/setup.sh installs (chromium, viewer/node_modules)
# and the release runner (cargo build --release --bin hybeam).
set -euo pipefail
cd "$(dirname "$0")/.."

echo "-- viewer bundle rebuilt from the lock file equals viewer/dist/viewer.js"
(cd viewer && npm run --silent build >/dev/null)
git diff --exit-code --stat -- viewer/dist/viewer.js

OUT=out/view-test
rm -rf "$OUT" && mkdir -p "$OUT"
for case in "case1 0.5" "strip_3d 0.3" "sprayer_boom_3d 0.2"; do
    set -- $case
    target/release/hybeam run "scenes/$1.toml" --t-end "$2" --out "$OUT/$1.csv" \
        --animate "$OUT/$1.html" --quiet
    echo "-- $1: the page in headless Chromium"
    (cd viewer && node test/page.test.mjs "../$OUT/$1.html" "../$OUT/$1.csv" "../$OUT/$1-shots")
done
