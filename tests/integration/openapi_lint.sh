#!/bin/sh
# openapi_lint.sh: GET /openapi.json from a running pointsegd, linted by
# Redocly's OpenAPI linter (@redocly/cli, pinned in
# tests/openapi/package-lock.json; `npm ci` uses npm's cache when offline)
# with its recommended rules: no error and no warning.  Installs npm as
# root when missing (scripts/web-deps.sh); SKIPs, saying why, when npm,
# a recent enough Node.js or the package cannot be had.
#   tests/integration/openapi_lint.sh BUILD
SUITE=openapi
. "$(dirname "$0")/lib.sh"
DIR=tests/openapi
daemon=""
trap '[ -n "$daemon" ] && kill "$daemon" 2>/dev/null; rm -rf "$tmp"' EXIT

# Node.js major.minor at least 20.19 (22.12 on 22 and later): Redocly's floor.
node_recent_enough() {
    node -e 'const [a, b] = process.versions.node.split(".").map(Number);
             process.exit(a > 22 || (a === 22 && b >= 12) || (a === 20 && b >= 19) ? 0 : 1)'
}

# Starts pointsegd on a free port; sets daemon (pid) and base (URL).
start_daemon() {
    "$BUILD/pointsegd" --port 0 --bind 127.0.0.1 --quiet 2>"$tmp/daemon.log" &
    daemon=$!
    for _ in $(seq 100); do
        base=$(sed -n 's/.*listening on \(http:[^ ]*\).*/\1/p' "$tmp/daemon.log")
        [ -n "$base" ] && return 0
        sleep 0.1
    done
    return 1
}

# Prints the totals line and the problems of Redocly's JSON report; exits
# 1 when there is any error or warning.
judge() {
    python3 -c '
import json, sys
report = json.load(open(sys.argv[1]))
t = report["totals"]
print("%d errors, %d warnings" % (t["errors"], t["warnings"]))
for p in report["problems"]:
    where = p["location"][0].get("pointer", "") if p.get("location") else ""
    print("  %s %s: %s %s" % (p["severity"], p["ruleId"], p["message"], where))
sys.exit(1 if t["errors"] or t["warnings"] else 0)
' "$1"
}

lint() {
    if ! scripts/web-deps.sh >"$tmp/deps.log" 2>&1 || ! command -v npm >/dev/null 2>&1; then
        skip lint "npm is missing and cannot be installed here: $(tail -1 "$tmp/deps.log")"
        return
    fi
    if ! node_recent_enough; then
        skip lint "@redocly/cli needs Node.js >= 20.19, this is $(node --version)"
        return
    fi
    if ! npm ci --prefix "$DIR" --prefer-offline --no-audit --no-fund --loglevel=error >"$tmp/npm.log" 2>&1; then
        skip lint "npm ci of $DIR failed (no registry, no cache?): $(tail -1 "$tmp/npm.log")"
        return
    fi
    if ! start_daemon; then
        fail lint "pointsegd did not start: $(tail -3 "$tmp/daemon.log")"
        return
    fi
    if ! curl -sf "$base/openapi.json" -o "$tmp/openapi.json"; then
        fail lint "GET $base/openapi.json failed"
        return
    fi
    REDOCLY_TELEMETRY=off REDOCLY_SUPPRESS_UPDATE_NOTICE=true \
        "$DIR/node_modules/.bin/redocly" lint --format=json "$tmp/openapi.json" \
        >"$tmp/report.json" 2>"$tmp/redocly.err"
    if [ ! -s "$tmp/report.json" ]; then
        fail lint "redocly wrote no report: $(grep -v '^ *$' "$tmp/redocly.err" | tail -3)"
    elif judge "$tmp/report.json" >"$tmp/judged"; then
        pass lint
    else
        fail lint "$(head -1 "$tmp/judged")"
        tail -n +2 "$tmp/judged" | head -20 >&2
    fi
}

lint
[ "$failures" -eq 0 ]
