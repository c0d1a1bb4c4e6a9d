#!/bin/sh
# run.sh: what `make test-browser` runs after `make web`: makes sure
# Chromium is there (installs it as root, else SKIPs), installs
# playwright-core (pinned in tests/browser/package-lock.json), and runs
# every tests/browser/*.test.mjs against BUILD/pointsegd.  Last line
# "N passed, N failed", the sum over the files.
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
out=$(mktemp)
trap 'rm -f "$out"' EXIT
passed=0 failed=0
for t in tests/browser/*.test.mjs; do
    timeout 170 node "$t" "$BUILD" | tee "$out"
    counts=$(grep -E '^[0-9]+ passed, [0-9]+ failed$' "$out" | tail -n 1)
    if [ -z "$counts" ]; then
        echo "FAIL browser:$(basename "$t"): ended without a count (timed out or crashed)"
        failed=$((failed + 1))
        continue
    fi
    passed=$((passed + ${counts%% passed*}))
    failed=$((failed + $(echo "$counts" | sed -E 's/.* ([0-9]+) failed$/\1/')))
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
