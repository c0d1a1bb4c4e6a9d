# scale.sh: the docker/compose.yaml topology without Docker: three pointsegd
# (replica names pointsegd-1..3) on loopback behind a real nginx running
# docker/nginx.conf with only its addresses, port and file paths rewritten.
#   sh tests/integration/scale.sh BUILD     (make test-scale)
# Checks `nginx -t` on that config and that every path the Dockerfile COPYs
# exists; sends 200 mixed requests (100 POST /segment, 100 jobs: POST /jobs,
# polls, result) through nginx with 8 clients; checks every answer's labels
# against a local `pointseg segment`, that every replica served some, and
# that every job was found (never a 404) on the replica named in its id.
# Installs nginx with apt-get when missing and run as root, else skips.
# Prints PASS/FAIL/SKIP lines and "N passed, N failed"; stops itself within
# about a minute.  Not executable on purpose: tests/run.sh (make test) runs
# only executable suites, and this one belongs to make test-scale.
set -u
BUILD=${1:-build}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
PS=$BUILD/pointseg
PSD=$BUILD/pointsegd
tmp=$(mktemp -d)
pids=""
passed=0 failed=0

cleanup() {
    for p in $pids; do kill "$p" 2>/dev/null; done
    wait 2>/dev/null
    rm -rf "$tmp"
}
trap cleanup EXIT
trap 'exit 1' INT TERM

pass() { echo "PASS scale:$1"; passed=$((passed + 1)); }
fail() { echo "FAIL scale:$1: $2"; failed=$((failed + 1)); }
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

find_nginx() {
    NGINX=$(command -v nginx || true)
    [ -z "$NGINX" ] && [ -x /usr/sbin/nginx ] && NGINX=/usr/sbin/nginx
    [ -n "$NGINX" ] && return 0
    if [ "$(id -u)" != 0 ]; then
        echo "SKIP scale:nginx: nginx is not installed and installing needs root:" \
             "sudo apt-get install -y nginx"
        return 1
    fi
    echo "scale: installing nginx (apt-get)" >&2
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends nginx \
        >"$tmp/apt.log" 2>&1 ||
        { apt-get update -qq >/dev/null 2>&1 &&
          DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends nginx \
              >"$tmp/apt.log" 2>&1; }
    NGINX=$(command -v nginx || echo /usr/sbin/nginx)
    [ -x "$NGINX" ] && return 0
    fail nginx "apt-get install nginx failed: $(tail -c 300 "$tmp/apt.log")"
    return 1
}

# start_replica N: pointsegd --replica-name pointsegd-N on a free port;
# sets port_N.
start_replica() {
    log=$tmp/replica-$1.log
    : >"$log"
    "$PSD" --port 0 --threads 1 --replica-name "pointsegd-$1" >"$log" 2>&1 &
    pids="$pids $!"
    for _ in $(seq 50); do
        port=$(sed -n 's/^pointsegd: listening on http:[^:]*:\([0-9]*\).*/\1/p' "$log")
        if [ -n "$port" ]; then
            eval "port_$1=$port"
            return 0
        fi
        sleep 0.1
    done
    fail "replica-$1" "did not start: $(head -c 300 "$log")"
    return 1
}

free_port() {
    python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}

# docker/nginx.conf with the replicas' loopback ports, nginx's own port and
# files under $tmp; routing untouched.
derive_nginx_conf() {
    for d in body proxy fastcgi uwsgi scgi; do mkdir -p "$tmp/$d" && chmod 1777 "$tmp/$d"; done
    chmod 755 "$tmp"
    sed -e "s/pointsegd-1:8080/127.0.0.1:$port_1/; s/pointsegd-2:8080/127.0.0.1:$port_2/" \
        -e "s/pointsegd-3:8080/127.0.0.1:$port_3/" \
        -e "s/listen 8080;/listen 127.0.0.1:$nginx_port;/" \
        -e "s|access_log /dev/stdout;|access_log $tmp/access.log;|" \
        -e "s|error_log /dev/stderr warn;|error_log $tmp/error.log warn;|" \
        -e "s|^http {|http {\n    client_body_temp_path $tmp/body;\n    proxy_temp_path $tmp/proxy;\n    fastcgi_temp_path $tmp/fastcgi;\n    uwsgi_temp_path $tmp/uwsgi;\n    scgi_temp_path $tmp/scgi;|" \
        "$ROOT/docker/nginx.conf" >"$tmp/nginx.conf"
    NGINX_GLOBALS="pid $tmp/nginx.pid; error_log $tmp/error.log;"
}

start_nginx() {
    "$NGINX" -p "$tmp" -c "$tmp/nginx.conf" -g "$NGINX_GLOBALS daemon off;" \
        >"$tmp/nginx.out" 2>&1 &
    pids="$pids $!"
    for _ in $(seq 50); do
        curl -fsS "http://127.0.0.1:$nginx_port/healthz" >/dev/null 2>&1 && return 0
        sleep 0.1
    done
    fail nginx "not answering: $(tail -c 300 "$tmp/error.log" "$tmp/nginx.out" 2>/dev/null)"
    return 1
}

check_docker_copies
for f in "$PS" "$PSD"; do
    [ -x "$f" ] || { fail setup "$f is not built"; finish; }
done
find_nginx || finish

# Two spheres of 150 points: a small job, two clear segments.
awk 'BEGIN {
    pi = atan2(0, -1); golden = pi * (3 - sqrt(5)); m = 150;
    for (s = 0; s < 2; s++) for (i = 0; i < m; i++) {
        y = 1 - 2 * (i + 0.5) / m; r = sqrt(1 - y * y); t = golden * i;
        printf "%.6f %.6f %.6f\n", 4 * s + r * cos(t), y, r * sin(t);
    }
}' >"$tmp/input.xyz"
"$PS" segment "$tmp/input.xyz" --output labels >"$tmp/expected.labels" ||
    { fail setup "local segment failed"; finish; }

start_replica 1 && start_replica 2 && start_replica 3 || finish
nginx_port=$(free_port)
derive_nginx_conf
if "$NGINX" -t -p "$tmp" -c "$tmp/nginx.conf" -g "$NGINX_GLOBALS" >"$tmp/t.log" 2>&1; then
    pass nginx-t
else
    fail nginx-t "$(tail -c 400 "$tmp/t.log")"
    finish
fi
start_nginx || finish

timeout 90 python3 - "http://127.0.0.1:$nginx_port" "$tmp" >"$tmp/driver.out" <<'PY'
import concurrent.futures, json, re, sys, time, urllib.error, urllib.request

base, tmp = sys.argv[1], sys.argv[2]
body = open(tmp + "/input.xyz", "rb").read()
expected = open(tmp + "/expected.labels").read().split()
REPLICAS = ("pointsegd-1", "pointsegd-2", "pointsegd-3")
N, CLIENTS, DEADLINE = 200, 8, time.monotonic() + 75


def call(method, path, data=None):
    req = urllib.request.Request(base + path, data=data, method=method)
    if data is not None:
        req.add_header("Content-Type", "application/octet-stream")
    try:
        with urllib.request.urlopen(req, timeout=20) as r:
            return r.status, r.read()
    except urllib.error.HTTPError as e:
        return e.code, e.read()


def sync_request(_):
    status, raw = call("POST", "/segment?output=labels", body)
    if status != 200:
        return "POST /segment answered %d: %.120r" % (status, raw), None
    if raw.decode().split() != expected:
        return "POST /segment labels differ from local", None
    return None, None


def async_request(_):
    status, raw = call("POST", "/jobs?output=labels", body)
    if status != 202:
        return "POST /jobs answered %d: %.120r" % (status, raw), None
    job = json.loads(raw)["id"]
    if not job.startswith(tuple(r + "-" for r in REPLICAS)):
        return "job id %s names no replica" % job, job
    while True:
        status, raw = call("GET", "/jobs/" + job)
        if status != 200:
            return "GET /jobs/%s answered %d (not found where polled)" % (job, status), job
        state = json.loads(raw)["status"]
        if state in ("done", "failed", "cancelled"):
            break
        if time.monotonic() > DEADLINE:
            return "job %s still %s at the deadline" % (job, state), job
        time.sleep(0.05)
    status, raw = call("GET", "/jobs/%s/result" % job)
    if status != 200 or raw.decode().split() != expected:
        return "job %s: result %d, labels %s" % (job, status, "differ" if status == 200 else "-"), job
    return None, job


def report(ok, name, why):
    print(("PASS scale:%s" % name) if ok else ("FAIL scale:%s: %s" % (name, why)), flush=True)


with concurrent.futures.ThreadPoolExecutor(CLIENTS) as pool:
    work = [pool.submit(sync_request if i % 2 else async_request, i) for i in range(N)]
    results = []
    for w in work:
        try:
            results.append(w.result())
        except Exception as e:  # a transport error is a wrong answer too
            results.append(("%s: %s" % (type(e).__name__, e), None))
errors = [e for e, _ in results if e]
jobs = [j for _, j in results if j]
report(not errors, "answers", "%d of %d wrong, first: %s" % (len(errors), N, errors[:1]))

logs = {r: open("%s/replica-%s.log" % (tmp, r[-1])).read() for r in REPLICAS}
served = {r: len(re.findall(r"^POST /(?:segment 200|jobs 202) ", logs[r], re.M)) for r in REPLICAS}
report(all(served.values()), "every-replica-served", "requests per replica %s" % served)
print("scale: requests per replica %s" % served, file=sys.stderr)

misplaced = []
for job in jobs:
    home = job[:len("pointsegd-N")]
    polled = {r: len(re.findall(r"^GET /jobs/%s 200 " % job, logs[r], re.M)) for r in REPLICAS}
    if polled[home] == 0 or sum(polled.values()) != polled[home]:
        misplaced.append((job, polled))
report(len(jobs) == N // 2 and not misplaced, "jobs-found-where-polled",
       "%d jobs, misplaced: %s" % (len(jobs), misplaced[:2]))
PY
rc=$?
cat "$tmp/driver.out"
passed=$((passed + $(grep -c '^PASS ' "$tmp/driver.out")))
failed=$((failed + $(grep -c '^FAIL ' "$tmp/driver.out")))
if [ "$rc" -eq 124 ]; then fail driver "timed out after 90 s"
elif [ "$rc" -ne 0 ]; then fail driver "exit status $rc"; fi
finish
