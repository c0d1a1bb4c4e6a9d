#!/bin/sh
# run.sh: what `make test-browser` runs after `make web`: makes sure
# Chromium is there (installs it as root, else SKIPs), installs
# playwright-core (pinned in tests/browser/package-lock.json), and runs
# viewer.test.mjs against BUILD/pointsegd.  Last line "N passed, N failed".
#   tests/browser/run.sh BUILD
set -eu
BUILD=${1:-build}
rc=0
scripts/web-deps.sh --browser || rc=$?
if [ "$rc" = 3 ]; then
    echo "SKIP browser: chromium is not installed and only root installs it"
    echo "0 passed, 0 failed, 1 skipped"
    exit 0
fi
[ "$rc" = 0 ] || exit "$rc"
npm ci --prefix tests/browser --no-audit --no-fund --loglevel=error
exec timeout 170 node tests/browser/viewer.test.mjs "$BUILD"
