# lib.sh: the opening the shell suites share; source it after setting SUITE.
#   SUITE=cli; . "$(dirname "$0")/lib.sh"
# Sets BUILD (the suite's first argument, default build), PS (BUILD/pointseg),
# a scratch directory $tmp removed on exit and failures=0; pass NAME,
# fail NAME WHY and skip NAME WHY print "PASS SUITE:NAME" and the like as
# tests/support/testlib.h does, fail counting in $failures.  Not executable:
# tests/run.sh runs only the executable *.sh.
set -u
BUILD=${1:-build}
PS=$BUILD/pointseg
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0

pass() { echo "PASS $SUITE:$1"; }
fail() { echo "FAIL $SUITE:$1: $2"; failures=$((failures + 1)); }
skip() { echo "SKIP $SUITE:$1: $2"; }
