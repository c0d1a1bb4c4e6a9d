#!/bin/sh
# run.sh: runs every test binary of a build and prints the count CI reads.
#   tests/run.sh BUILD             unit tests (plain, BUILD/san, and BUILD/tsan for
#                                  the threaded code's), integration
#                                  tests (plain, then BUILD/san's and
#                                  BUILD/tsan's, whose daemons run under the
#                                  sanitizers), short fuzz runs, extra suites
#                                  (the CLI's, clients' and render's also with
#                                  BUILD/san's programs)
#   tests/run.sh --unit-only BUILD unit tests of BUILD only
# Each test prints PASS/FAIL/SKIP lines (tests/support/testlib.h); a binary that
# dies without saying FAIL counts as one failure.  The last line is
# "N passed, N failed, N skipped".
set -u
unit_only=0
[ "${1:-}" = "--unit-only" ] && { unit_only=1; shift; }
BUILD=${1:-build}
log=$(mktemp -d)
trap 'rm -rf "$log"' EXIT
passed=0 failed=0 skipped=0
. "$(dirname "$0")/sanitizer_options.sh"

run_one() { # label command...
    label=$1; shift
    out="$log/out"
    "$@" >"$out" 2>"$log/err"
    rc=$?
    p=$(grep -c '^PASS ' "$out") f=$(grep -c '^FAIL ' "$out") s=$(grep -c '^SKIP ' "$out")
    grep -E '^(FAIL|SKIP) ' "$out"
    if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
        echo "FAIL $label: exited with status $rc"
        tail -n 20 "$log/err" | sed 's/^/    /'
        f=$((f + 1))
    elif [ "$f" -ne 0 ]; then
        sed 's/^/    /' "$log/err" | tail -n 40
    fi
    if [ "$p" -eq 0 ] && [ "$f" -eq 0 ] && [ "$s" -eq 0 ]; then
        echo "FAIL $label: ran no test"
        f=1
    fi
    echo "  $label: $p passed, $f failed, $s skipped"
    passed=$((passed + p)) failed=$((failed + f)) skipped=$((skipped + s))
}

run_dir() { # title dir sources: the binaries of dir and its folders whose source is in sources
    [ -d "$2" ] || return 0
    echo "== $1"
    for t in "$2"/* "$2"/*/*; do
        name=${t#"$2"/}
        # a binary left by a test since deleted is not this checkout's test
        [ -f "$3/$name.c" ] || continue
        [ -x "$t" ] && [ -f "$t" ] && run_one "$1/$name" "$t"
    done
}

run_dir "unit" "$BUILD/tests" tests/unit
if [ "$unit_only" = 0 ]; then
    run_dir "unit (asan+ubsan)" "$BUILD/san/tests" tests/unit
    run_dir "unit (tsan)" "$BUILD/tsan/tests" tests/unit
    run_dir "integration" "$BUILD/itests" tests/integration
    run_dir "integration (asan+ubsan)" "$BUILD/san/itests" tests/integration
    run_dir "integration (tsan)" "$BUILD/tsan/itests" tests/integration
    for suite in tests/layout.sh tests/integration/*.sh tests/fuzz/run.sh; do
        [ -x "$suite" ] || continue
        echo "== $suite"
        run_one "$suite" "$suite" "$BUILD"
    done
    # The suites that run the programs, again with BUILD/san's.
    for suite in tests/integration/cli.sh tests/integration/clients.sh tests/integration/render.sh; do
        [ -x "$suite" ] && [ -x "$BUILD/san/pointseg" ] || continue
        echo "== $suite (asan+ubsan)"
        run_one "$suite (asan+ubsan)" "$suite" "$BUILD/san"
    done
fi
echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]
