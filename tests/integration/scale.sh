# scale.sh: the docker/compose.yaml topology without Docker: redis-server,
# three identical pointsegd --redis on loopback, and a real nginx running
# docker/nginx.conf with only its replica line, port and file paths
# rewritten.
#   sh tests/integration/scale.sh BUILD [BUILD...]   (make test-scale: the
#       plain build, then BUILD/san and BUILD/tsan, whose daemons run under
#       AddressSanitizer + UBSan and ThreadSanitizer)
# Checks that every path the Dockerfile COPYs exists, then runs
# scale_driver.py: 300 mixed requests through nginx (sync and async, valid
# and invalid, cancels), a job read from every replica, a replica SIGKILLed
# while it runs a job (the job finishes on another), redis-server restarted
# mid-run, no job lost or wrong, and no sanitizer finding in a replica's log
# (see the driver's top comment); once for each BUILD, its checks named
# scale:... for the first and scale(DIR):... for BUILD/DIR after it.
# Installs nginx and redis-server with apt-get when missing and run as root,
# else skips.  Prints PASS/FAIL/SKIP lines and "N passed, N failed"; stops
# each BUILD's run within about five minutes.  Not executable on purpose:
# tests/run.sh (make test) runs only executable suites, and this one belongs
# to make test-scale.
set -u
[ $# -gt 0 ] || set -- build
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
passed=0 failed=0

trap 'rm -rf "$tmp"' EXIT
trap 'exit 1' INT TERM

# A check's name is SUITE:NAME, SUITE "scale" or "scale(DIR)" (below).
suite=scale
pass() { echo "PASS $suite:$1"; passed=$((passed + 1)); }
fail() { echo "FAIL $suite:$1: $2"; failed=$((failed + 1)); }
finish() {
    echo "$passed passed, $failed failed"
    [ "$failed" -eq 0 ]
    exit
}

# Every source of a COPY without --from in the Dockerfile exists.
check_docker_copies() {
    missing=$(awk '$1 == "COPY" && $2 !~ /^--from/ {
                       for (i = 2; i < NF; i++) if ($i !~ /^--/) print $i }' \
                  "$ROOT/docker/Dockerfile" |
              while read -r src; do [ -e "$ROOT/$src" ] || printf '%s ' "$src"; done)
    n=$(grep -c '^COPY ' "$ROOT/docker/Dockerfile")
    if [ "$n" -gt 0 ] && [ -z "$missing" ]; then pass dockerfile-copies
    else fail dockerfile-copies "missing: ${missing:-no COPY lines}"; fi
}

# need PROGRAM PACKAGE: the program is on PATH (or /usr/sbin), installed
# with apt-get when missing and root; else a SKIP line and status 1.
need() {
    PATH=$PATH:/usr/sbin command -v "$1" >/dev/null && return 0
    if [ "$(id -u)" != 0 ]; then
        echo "SKIP scale:$2: $1 is not installed and installing needs root:" \
             "sudo apt-get install -y $2"
        return 1
    fi
    echo "scale: installing $2 (apt-get)" >&2
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "$2" \
        >"$tmp/apt.log" 2>&1 ||
        { apt-get update -qq >/dev/null 2>&1 &&
          DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "$2" \
              >"$tmp/apt.log" 2>&1; }
    PATH=$PATH:/usr/sbin command -v "$1" >/dev/null && return 0
    fail "$2" "apt-get install $2 failed: $(tail -c 300 "$tmp/apt.log")"
    return 1
}

# drive BUILD: the topology with BUILD's programs, its checks named
# $suite:..., its files in $tmp/$suite.
drive() {
    for f in "$1/pointseg" "$1/pointsegd"; do
        [ -x "$f" ] || { fail setup "$f is not built"; return; }
    done
    dir="$tmp/$suite"
    mkdir -p "$dir" && chmod 755 "$dir"
    timeout 300 python3 "$ROOT/tests/integration/scale_driver.py" "$1" "$dir" "$NGINX" \
        "$ROOT/docker/nginx.conf" "$suite" >"$dir/driver.out"
    rc=$?
    cat "$dir/driver.out"
    passed=$((passed + $(grep -c '^PASS ' "$dir/driver.out")))
    failed=$((failed + $(grep -c '^FAIL ' "$dir/driver.out")))
    if [ "$rc" -eq 124 ]; then fail driver "timed out after 300 s"
    elif [ "$rc" -ne 0 ]; then fail driver "exit status $rc"; fi
}

check_docker_copies
need nginx nginx && need redis-server redis-server || finish
NGINX=$(PATH=$PATH:/usr/sbin command -v nginx)
chmod 755 "$tmp"
. "$ROOT/tests/sanitizer_options.sh"
first=$1
for build in "$@"; do
    if [ "$build" = "$first" ]; then suite=scale; else suite="scale(${build#"$first"/})"; fi
    drive "$build"
done
finish
