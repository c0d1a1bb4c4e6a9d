# run.sh: make test-docker: builds docker/Dockerfile, runs the image and
# segments the horse through it, checks its HEALTHCHECK on another
# POINTSEG_PORT and on docker run's --bind 127.0.0.2 (the daemon as PID 1,
# whose command line the check reads), then brings up docker/compose.yaml
# (redis, 3 pointsegd replicas, nginx) and runs compose_driver.py's checks
# on it, `docker kill` included.  First lint_deploy.py reads docker/'s files against
# `pointsegd --help` and the routes (no Docker needed).
#   sh tests/docker/run.sh BUILD
# Needs root: installs docker.io, docker-compose and debootstrap with
# apt-get when missing and starts dockerd when it is not running (and
# stops the one it started at the end; the images stay in Docker's store).
# No image registry is reachable, so the Debian base
# images come from debootstrap and the redis and nginx images from Debian's
# packages (base-images.sh; made once, then cached in Docker's image store:
# the first run takes about 4 minutes more).  Prints PASS/FAIL/SKIP lines
# and "N passed, N failed, N skipped"; a SKIP says what stopped it.
set -u
BUILD=${1:-build}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
project=pointsegtest$$
passed=0 failed=0 skipped=0
single=""
dockerd_pid=""
COMPOSE_FILES="-f $ROOT/docker/compose.yaml -f $ROOT/tests/docker/compose.test.yaml"
# Debian's client first: its BuildKit reads docker/Dockerfile.dockerignore.
PATH=/usr/bin:/usr/sbin:$PATH

cleanup() {
    [ -n "$single" ] && docker rm -f "$single" >/dev/null 2>&1
    # shellcheck disable=SC2086
    command -v docker-compose >/dev/null &&
        docker-compose -p "$project" $COMPOSE_FILES down -v -t 5 >/dev/null 2>&1
    stop_dockerd
    rm -rf "$tmp"
}

# Stops the dockerd this script started (none when one was running).
stop_dockerd() {
    [ -n "$dockerd_pid" ] || return 0
    kill "$dockerd_pid" 2>/dev/null
    for _ in $(seq 40); do
        kill -0 "$dockerd_pid" 2>/dev/null || return 0
        sleep 0.5
    done
    kill -9 "$dockerd_pid" 2>/dev/null
}
trap cleanup EXIT
trap 'exit 1' INT TERM

pass() { echo "PASS docker:$1"; passed=$((passed + 1)); }
fail() { echo "FAIL docker:$1: $2"; failed=$((failed + 1)); }
finish() {
    echo "$passed passed, $failed failed, $skipped skipped"
    [ "$failed" -eq 0 ]
    exit
}
skip_rest() { echo "SKIP docker:$1: $2"; skipped=$((skipped + 1)); finish; }

install_missing() {
    missing=""
    command -v dockerd >/dev/null || missing="$missing docker.io"
    command -v docker-compose >/dev/null || missing="$missing docker-compose"
    command -v debootstrap >/dev/null || missing="$missing debootstrap"
    [ -z "$missing" ] && return 0
    echo "docker: installing$missing (apt-get)" >&2
    # shellcheck disable=SC2086
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $missing \
        >"$tmp/apt.log" 2>&1 ||
        { apt-get update -qq >/dev/null 2>&1 &&
          DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $missing \
              >"$tmp/apt.log" 2>&1; } ||
        skip_rest install "apt-get install$missing failed: $(tail -c 300 "$tmp/apt.log")"
}

start_dockerd() {
    docker info >/dev/null 2>&1 && return 0
    echo "docker: starting dockerd (log /var/log/pointseg-dockerd.log)" >&2
    nohup dockerd >/var/log/pointseg-dockerd.log 2>&1 &
    dockerd_pid=$!
    for _ in $(seq 60); do
        docker info >/dev/null 2>&1 && return 0
        sleep 0.5
    done
    skip_rest dockerd "dockerd does not start here: $(tail -n 3 /var/log/pointseg-dockerd.log | tr '\n' ' ')"
}

free_port() {
    python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}

wait_http() { # URL SECONDS
    end=$(($(date +%s) + $2))
    while [ "$(date +%s)" -lt "$end" ]; do
        curl -fsS "$1" >/dev/null 2>&1 && return 0
        sleep 0.5
    done
    return 1
}

# The image alone: the horse (or the sample) through it, labels as local.
run_single() {
    input=${POINTSEG_SHARED:-$ROOT/../shared/data}/models/horse.ply
    [ -f "$input" ] || input=$ROOT/clients/curl/sample.xyz
    single=$(docker run -d -p 127.0.0.1::8080 pointseg:latest) || { fail run "docker run failed"; return; }
    port=$(docker port "$single" 8080 | head -n 1 | sed 's/.*://')
    wait_http "http://127.0.0.1:$port/healthz" 30 || { fail run "no /healthz: $(docker logs "$single" 2>&1 | tail -n 3)"; return; }
    [ "$(docker exec "$single" id -u)" = 10001 ] && pass runs-as-non-root || fail runs-as-non-root "uid $(docker exec "$single" id -u)"
    # docker/k8s/deployment.yaml's preStop hook runs `sleep` in the container.
    docker exec "$single" sleep 0 && pass image-has-prestop-sleep ||
        fail image-has-prestop-sleep "docker exec sleep 0 failed"
    curl -fsS -X POST -H 'Content-Type: application/octet-stream' --data-binary "@$input" \
        "http://127.0.0.1:$port/segment?output=labels" >"$tmp/docker.labels" 2>"$tmp/curl.err"
    "$BUILD/pointseg" segment "$input" --output labels >"$tmp/local.labels"
    if [ -s "$tmp/docker.labels" ] && cmp -s "$tmp/docker.labels" "$tmp/local.labels"; then
        pass "run-segments-$(basename "$input")"
    else
        fail "run-segments-$(basename "$input")" "labels differ from the local run ($(cat "$tmp/curl.err"))"
    fi
    # The viewer's three.js, when `make web` put it in clients/web/vendor/.
    if [ -f "$ROOT/clients/web/vendor/three.module.js" ]; then
        code=$(curl -s -o /dev/null -w '%{http_code}' "http://127.0.0.1:$port/vendor/three.module.js")
        [ "$code" = 200 ] && pass run-serves-three-js || fail run-serves-three-js "answered $code"
    fi
    docker rm -f "$single" >/dev/null 2>&1
    single=""
}

# The image's HEALTHCHECK (run every second here) says healthy with the
# daemon started by `docker run -d ARGS...`.
run_health() { # NAME ARGS...
    name=$1
    shift
    single=$(docker run -d --health-interval 1s "$@") || { fail "$name" "docker run failed"; return; }
    status=starting
    for _ in $(seq 40); do
        status=$(docker inspect -f '{{.State.Health.Status}}' "$single")
        [ "$status" = starting ] || break
        sleep 0.5
    done
    [ "$status" = healthy ] && pass "$name" || fail "$name" "docker run $*: $status"
    docker rm -f "$single" >/dev/null 2>&1
    single=""
}

run_compose() {
    port=$(free_port)
    # shellcheck disable=SC2086
    PUBLISH=127.0.0.1:$port docker-compose -p "$project" $COMPOSE_FILES up -d --no-build \
        --scale pointsegd=3 >"$tmp/up.log" 2>&1 ||
        { fail compose-up "$(tail -c 400 "$tmp/up.log")"; return; }
    wait_http "http://127.0.0.1:$port/readyz" 120 ||
        { fail compose-up "nginx not ready: $(tail -c 400 "$tmp/up.log")"; return; }
    pass compose-up
    # shellcheck disable=SC2086
    timeout 600 python3 "$ROOT/tests/docker/compose_driver.py" "$project" $COMPOSE_FILES -- \
        "http://127.0.0.1:$port" "$tmp" "$BUILD/pointseg" >"$tmp/driver.out"
    rc=$?
    cat "$tmp/driver.out"
    passed=$((passed + $(grep -c '^PASS ' "$tmp/driver.out")))
    failed=$((failed + $(grep -c '^FAIL ' "$tmp/driver.out")))
    [ "$rc" -eq 0 ] || fail compose-driver "exit status $rc"
}

[ "$(id -u)" = 0 ] || skip_rest setup "needs root (dockerd, apt-get, debootstrap)"
[ -x "$BUILD/pointseg" ] || { fail setup "$BUILD/pointseg is not built"; finish; }
install_missing
# The deployment files against the daemon (no Docker needed).
python3 "$ROOT/tests/docker/lint_deploy.py" "$ROOT" "$BUILD/pointsegd" >"$tmp/lint.out" 2>&1
rc=$?
cat "$tmp/lint.out"
passed=$((passed + $(grep -c '^PASS ' "$tmp/lint.out")))
failed=$((failed + $(grep -c '^FAIL ' "$tmp/lint.out")))
skipped=$((skipped + $(grep -c '^SKIP ' "$tmp/lint.out")))
[ "$rc" -eq 0 ] || fail lint-deploy "exit status $rc"
start_dockerd
. "$ROOT/tests/docker/base-images.sh"
make_debian_base 2>"$tmp/base.err" ||
    skip_rest base-images "no debian:bookworm image: $(tail -c 300 "$tmp/base.err")"
make_stand_ins >"$tmp/stand-ins.log" 2>&1 ||
    skip_rest base-images "stand-in redis/nginx images: $(tail -c 300 "$tmp/stand-ins.log")"
if DOCKER_BUILDKIT=1 docker build -q -f "$ROOT/docker/Dockerfile" -t pointseg:latest "$ROOT" \
        >"$tmp/build.log" 2>&1; then
    pass build
else
    fail build "$(tail -c 400 "$tmp/build.log")"
    finish
fi
run_single
run_health healthcheck-follows-port -e POINTSEG_PORT=9090 pointseg:latest
run_health healthcheck-follows-bind-flag pointseg:latest --bind 127.0.0.2 --port 9091
run_compose
finish
