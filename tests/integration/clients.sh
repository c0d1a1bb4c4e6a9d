#!/bin/sh
# clients.sh: the clients of clients/ against a running daemon.
#   tests/integration/clients.sh BUILD     uses BUILD/pointsegd, BUILD/pointseg
# Starts two pointsegd on free ports (one with --token), runs every curl
# script, the Python client (CLI sync and async, and imported) and
# `pointseg segment --server` (sync, async, token), and checks each answer's
# labels equal a local `pointseg segment --output labels` of the same input;
# stand-ins that close, hold or answer jobs wrongly check the clients' errors.
# Prints "PASS clients:NAME" / "FAIL clients:NAME: why"; exits 1 on any
# failure; stops the daemons and stand-ins.
set -u
BUILD=${1:-build}
PS=$BUILD/pointseg
PSD=$BUILD/pointsegd
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
SAMPLE=$ROOT/clients/curl/sample.xyz
TOKEN=clients-test-token
tmp=$(mktemp -d)
pids=""
trap 'for p in $pids; do kill "$p" 2>/dev/null; done; rm -rf "$tmp"' EXIT
failures=0

pass() { echo "PASS clients:$1"; }
fail() { echo "FAIL clients:$1: $2"; failures=$((failures + 1)); }

# start_daemon NAME ARGS...: starts pointsegd on a free port; sets $url.
start_daemon() {
    name=$1
    shift
    : >"$tmp/$name.log"
    "$PSD" --port 0 --quiet "$@" >"$tmp/$name.log" 2>&1 &
    pids="$pids $!"
    url=""
    for _ in $(seq 50); do
        url=$(sed -n 's/^pointsegd: listening on \(http:[^ ]*\).*/\1/p' "$tmp/$name.log")
        [ -n "$url" ] && return 0
        sleep 0.1
    done
    fail "$name" "daemon did not start: $(head -c 300 "$tmp/$name.log")"
    return 1
}

# same_labels NAME FILE: FILE holds labels (one per line) equal to the
# local ones.
same_labels() {
    if cmp -s "$2" "$tmp/local.labels"; then pass "$1"
    else fail "$1" "labels differ from local: $(head -c 120 "$2" | tr '\n' ' ')"; fi
}

# json_labels FILE: the "labels" array of a JSON document, one per line.
json_labels() {
    python3 -c 'import json, sys; print(*json.load(open(sys.argv[1]))["labels"], sep="\n")' "$1"
}

# check NAME CMD...: runs CMD (at most 60 s) with stdout to $tmp/NAME.out;
# fails NAME on a non-zero exit (returns 1), else returns 0.
check() {
    name=$1
    shift
    timeout 60 "$@" >"$tmp/$name.out" 2>"$tmp/$name.err"
    status=$?
    [ "$status" -eq 0 ] && return 0
    fail "$name" "exit status $status: $(tail -c 300 "$tmp/$name.err")"
    return 1
}

# check names the command's own exit status when it fails (in a subshell,
# so that this failure it reports is not counted).
said=$(check check-status sh -c 'echo oops >&2; exit 3')
case $said in
*"exit status 3: oops"*) pass check-reports-status ;;
*) fail check-reports-status "check said: $said" ;;
esac

for f in "$PS" "$PSD"; do
    [ -x "$f" ] || { fail setup "$f is not built"; exit 1; }
done
"$PS" segment "$SAMPLE" --output labels >"$tmp/local.labels" || { fail setup "local segment"; exit 1; }
[ "$(sort -u "$tmp/local.labels" | wc -l)" -ge 2 ] || fail setup "the sample has one segment"

start_daemon plain || exit 1
plain=$url
start_daemon token --token "$TOKEN" || exit 1
secured=$url

# ---- curl scripts ----
curl_dir=$ROOT/clients/curl
check curl-segment "$curl_dir/segment.sh" "$plain" &&
    json_labels "$tmp/curl-segment.out" >"$tmp/a" && same_labels curl-segment "$tmp/a"
PARAMS=output=labels check curl-segment-labels "$curl_dir/segment.sh" "$plain" "$SAMPLE" &&
    same_labels curl-segment-labels "$tmp/curl-segment-labels.out"
PARAMS=output=labels check curl-jobs "$curl_dir/jobs.sh" "$plain" &&
    same_labels curl-jobs "$tmp/curl-jobs.out"
if check curl-ply "$curl_dir/ply.sh" "$plain" "$SAMPLE" "$tmp/parts.ply"; then
    if head -c 200 "$tmp/parts.ply" | grep -q '^element vertex 2000$' &&
        "$PS" render "$tmp/parts.ply" -o "$tmp/parts.png" 2>/dev/null; then pass curl-ply
    else fail curl-ply "not a 2000-vertex PLY that renders: $(head -c 100 "$tmp/parts.ply")"; fi
fi
printf 'not a point set\n' >"$tmp/bad.xyz"
if "$curl_dir/jobs.sh" "$plain" "$tmp/bad.xyz" >/dev/null 2>"$tmp/e"; then
    fail curl-jobs-bad-input "bad input was accepted"
elif grep -q 'unrecognized format' "$tmp/e"; then pass curl-jobs-bad-input
else fail curl-jobs-bad-input "the problem's detail is not on stderr: $(head -c 200 "$tmp/e")"; fi
echo kept >"$tmp/kept.ply"
if "$curl_dir/ply.sh" "$plain" "$tmp/bad.xyz" "$tmp/kept.ply" >/dev/null 2>"$tmp/e"; then
    fail curl-ply-bad-input "bad input was accepted"
elif ! grep -q 'unrecognized format' "$tmp/e"; then
    fail curl-ply-bad-input "the problem's detail is not on stderr: $(head -c 200 "$tmp/e")"
elif [ "$(cat "$tmp/kept.ply")" != kept ]; then
    fail curl-ply-bad-input "OUT was overwritten: $(head -c 100 "$tmp/kept.ply")"
else pass curl-ply-bad-input; fi
PARAMS=output=labels POINTSEG_TOKEN=$TOKEN check curl-token "$curl_dir/token.sh" "$secured" &&
    same_labels curl-token "$tmp/curl-token.out"
PARAMS=output=labels POINTSEG_TOKEN=$TOKEN check curl-token-bash bash "$curl_dir/token.sh" "$secured" &&
    same_labels curl-token-bash "$tmp/curl-token-bash.out"
if POINTSEG_TOKEN=wrong "$curl_dir/token.sh" "$secured" >/dev/null 2>&1; then
    fail curl-token-wrong "a wrong token was accepted"
else pass curl-token-wrong; fi

# ---- Python client ----
py=$ROOT/clients/python/pointseg_client.py
check python-sync python3 "$py" segment "$SAMPLE" --server "$plain" --output labels &&
    same_labels python-sync "$tmp/python-sync.out"
check python-async python3 "$py" segment "$SAMPLE" --server "$plain" --async --output labels &&
    same_labels python-async "$tmp/python-async.out"
check python-token python3 "$py" segment "$SAMPLE" --server "$secured" --token "$TOKEN" \
    --output json -o "$tmp/py.json" && json_labels "$tmp/py.json" >"$tmp/b" &&
    same_labels python-token "$tmp/b"
# The daemon answers a body of megabytes without the token from its head
# (401) and closes: the client reads that answer, where it failed with
# "cannot reach ...: Broken pipe" (status 0, exit 1).
python3 -c '
import random, sys
random.seed(1)
with open(sys.argv[1], "w") as f:
    for _ in range(300000):
        f.write("%.6f %.6f %.6f\n" % (random.random(), random.random(), random.random()))
' "$tmp/big.xyz"
python3 "$py" segment "$tmp/big.xyz" --server "$secured" >/dev/null 2>"$tmp/e"
rc=$?
if [ "$rc" -eq 2 ] && grep -q "HTTP 401" "$tmp/e"; then pass python-early-answer
else fail python-early-answer "exit status $rc: $(head -c 200 "$tmp/e")"; fi
# As with pointseg's flags, of a parameter given twice only the last is sent
# (the daemon refuses a second): --param NAME twice, ncut-threshold and
# ncut_threshold, --output and --param output= in either order.
check python-param-twice python3 "$py" segment "$SAMPLE" --server "$plain" --param k=0 \
    --param k=7 --param ncut-threshold=0.9 --param ncut_threshold=0 --output labels &&
    same_labels python-param-twice "$tmp/python-param-twice.out"
check python-param-output python3 "$py" segment "$SAMPLE" --server "$plain" \
    --param output=json --output labels &&
    same_labels python-param-output "$tmp/python-param-output.out"
check python-output-param python3 "$py" segment "$SAMPLE" --server "$plain" \
    --output json --param output=labels &&
    same_labels python-output-param "$tmp/python-output-param.out"
# A --param named like one of segment()'s own arguments is still a
# parameter for the daemon (an unknown one), not the client's token.
python3 "$py" segment "$SAMPLE" --server "$plain" --param token=x >/dev/null 2>"$tmp/e"
rc=$?
if [ "$rc" -eq 2 ] && grep -q "unknown parameter 'token'" "$tmp/e"; then pass python-param-token
else fail python-param-token "exit status $rc: $(head -c 200 "$tmp/e")"; fi
check python-import python3 -c '
import sys
sys.path.insert(0, sys.argv[1])
import pointseg_client as pc
points = [list(map(float, line.split())) for line in open(sys.argv[2])]
doc = pc.segment(points, server=sys.argv[3])
assert doc["n_points"] == len(points), doc["n_points"]
print(*doc["labels"], sep="\n")
labels = pc.segment(sys.argv[2], server=sys.argv[3], output="labels", async_=True)
assert labels == doc["labels"], "async labels differ"
try:
    pc.segment(sys.argv[2], server=sys.argv[3], k=0)
    sys.exit("k=0 was accepted")
except pc.PointsegError as e:
    assert e.status == 422, e.status
' "$ROOT/clients/python" "$SAMPLE" "$plain" && same_labels python-import "$tmp/python-import.out"

# No answer (the connection closed, or nothing within the timeout) is a
# PointsegError with status 0 and, on the command line, exit status 1.
cat >"$tmp/mute.py" <<'MUTE'
import socket, sys
server = socket.socket()
server.bind(("127.0.0.1", 0))
server.listen(8)
print(server.getsockname()[1], flush=True)
held = []
while True:
    conn, _ = server.accept()
    conn.recv(65536)
    if sys.argv[1] == "close":
        conn.close()
    else:
        held.append(conn)
MUTE
# port_of FILE: the port a stand-in printed into FILE, waiting up to 10 s
# for it (a loaded machine starts python slowly).
port_of() {
    for _ in $(seq 100); do
        [ -s "$1" ] && break
        sleep 0.1
    done
    cat "$1"
}
python3 "$tmp/mute.py" close >"$tmp/close.port" &
pids="$pids $!"
python3 "$tmp/mute.py" hold >"$tmp/hold.port" &
pids="$pids $!"
closing=http://127.0.0.1:$(port_of "$tmp/close.port")
holding=http://127.0.0.1:$(port_of "$tmp/hold.port")
check python-no-answer python3 -c '
import sys
sys.path.insert(0, sys.argv[1])
import pointseg_client as pc
for server, timeout in ((sys.argv[3], None), (sys.argv[4], 0.5)):
    try:
        pc.segment(sys.argv[2], server=server, timeout=timeout)
        sys.exit("an answer from " + server)
    except pc.PointsegError as e:
        assert e.status == 0 and server in str(e), e
' "$ROOT/clients/python" "$SAMPLE" "$closing" "$holding" && pass python-no-answer
python3 "$py" segment "$SAMPLE" --server "$closing" >/dev/null 2>"$tmp/e"
rc=$?
if [ "$rc" -eq 1 ] && grep -q "no answer from $closing" "$tmp/e"; then pass python-cli-no-answer
else fail python-cli-no-answer "exit status $rc: $(head -c 200 "$tmp/e")"; fi

# A stand-in daemon whose job answers go wrong; the first segment of the
# path (the server URL's own path) says how:
#   stall-poll    POST .../jobs: 202 with an id; GET .../jobs/ID: no answer
#   stall-result  GET .../jobs/ID: done; GET .../jobs/ID/result: no answer
#   no-id         POST .../jobs: 202 without an id
#   bad-status    GET .../jobs/ID: 200, not JSON
#   trickle       POST .../segment: 200 whose body comes a byte every 0.2 s
cat >"$tmp/wrong.py" <<'WRONG'
import http.server, time

class Answers(http.server.BaseHTTPRequestHandler):
    protocol_version = "HTTP/1.1"

    def log_message(self, *args):
        pass

    def answer(self, status, body):
        self.send_response(status)
        self.send_header("Content-Type", "application/json")
        self.send_header("Content-Length", str(len(body)))
        self.end_headers()
        self.wfile.write(body)

    def do_POST(self):
        self.rfile.read(int(self.headers.get("Content-Length", 0)))
        if self.path.startswith("/trickle/"):
            self.send_response(200)
            self.send_header("Content-Type", "application/json")
            self.send_header("Content-Length", "100000")
            self.end_headers()
            try:
                for _ in range(100000):
                    self.wfile.write(b" ")
                    self.wfile.flush()
                    time.sleep(0.2)
            except OSError:
                pass  # the client gave up
        elif self.path.startswith("/no-id/"):
            self.answer(202, b'{"status": "queued"}')
        else:
            self.answer(202, b'{"id": "j1", "status": "queued"}')

    def do_GET(self):
        mode = self.path.split("/")[1]
        result = self.path.endswith("/result")
        if mode == "stall-poll" or (mode == "stall-result" and result):
            time.sleep(3600)
        elif mode == "bad-status":
            self.answer(200, b"not JSON")
        else:
            self.answer(200, b'{"labels": []}' if result else b'{"id": "j1", "status": "done"}')

server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Answers)
server.daemon_threads = True
print(server.server_address[1], flush=True)
server.serve_forever()
WRONG
python3 "$tmp/wrong.py" >"$tmp/wrong.port" &
pids="$pids $!"
wrong=http://127.0.0.1:$(port_of "$tmp/wrong.port")

# segment(async_=True, timeout=...) is bounded by the timeout, polls and
# result request included (they had none: a stalled daemon hung it).
check python-async-timeout timeout 10 python3 -c '
import sys, time
sys.path.insert(0, sys.argv[1])
import pointseg_client as pc
for mode in ("stall-poll", "stall-result"):
    start = time.monotonic()
    try:
        pc.segment(sys.argv[2], server=sys.argv[3] + "/" + mode, async_=True, timeout=1)
        sys.exit(mode + ": an answer")
    except pc.PointsegError as e:
        assert e.status == 0, e
    took = time.monotonic() - start
    assert took < 3, "%s: a 1 s timeout took %.1f s" % (mode, took)
' "$ROOT/clients/python" "$SAMPLE" "$wrong" && pass python-async-timeout

# A daemon that sends its answer a byte at a time cannot hold segment()
# past its timeout (each read waited the timeout on its own: the call ran
# on as long as bytes came).
check python-trickle-timeout timeout 10 python3 -c '
import sys, time
sys.path.insert(0, sys.argv[1])
import pointseg_client as pc
start = time.monotonic()
try:
    pc.segment(sys.argv[2], server=sys.argv[3] + "/trickle", timeout=1)
    sys.exit("an answer")
except pc.PointsegError as e:
    assert e.status == 0, e
took = time.monotonic() - start
assert took < 3, "a 1 s timeout took %.1f s" % took
' "$ROOT/clients/python" "$SAMPLE" "$wrong" && pass python-trickle-timeout

# A job answer without its id or status (not JSON) is a PointsegError with
# status 0, and the command line exits 1 naming it (it was a raw KeyError
# or ValueError traceback).
check python-unreadable-job-answers timeout 10 python3 -c '
import sys
sys.path.insert(0, sys.argv[1])
import pointseg_client as pc
for mode, member in (("no-id", "id"), ("bad-status", "status")):
    try:
        pc.segment(sys.argv[2], server=sys.argv[3] + "/" + mode, async_=True, timeout=5)
        sys.exit(mode + ": an answer")
    except pc.PointsegError as e:
        assert e.status == 0 and "without a readable " + member in str(e), e
' "$ROOT/clients/python" "$SAMPLE" "$wrong" && pass python-unreadable-job-answers
timeout 10 python3 "$ROOT/clients/python/pointseg_client.py" segment "$SAMPLE" --server "$wrong/no-id" \
    --async >/dev/null 2>"$tmp/e"
rc=$?
if [ "$rc" -eq 1 ] && grep -q "without a readable id" "$tmp/e"; then pass python-cli-unreadable-job
else fail python-cli-unreadable-job "exit status $rc: $(head -c 200 "$tmp/e")"; fi

# ---- pointseg segment --server ----
check cli-server "$PS" segment "$SAMPLE" --server "$plain" --output labels &&
    same_labels cli-server "$tmp/cli-server.out"
check cli-server-async "$PS" segment "$SAMPLE" --server "$plain" --async --output labels &&
    same_labels cli-server-async "$tmp/cli-server-async.out"
POINTSEG_TOKEN=$TOKEN check cli-server-token "$PS" segment "$SAMPLE" --server "$secured" \
    --output labels && same_labels cli-server-token "$tmp/cli-server-token.out"
# Flags override the JSON input's "params" and earlier flags, as locally
# (the daemon refuses a parameter given twice).
python3 -c '
import json, sys
points = [list(map(float, line.split())) for line in open(sys.argv[1])]
json.dump({"points": points, "params": {"k": 8, "ncut-threshold": 0.2}}, open(sys.argv[2], "w"))
' "$SAMPLE" "$tmp/params.json"
# same_as_local NAME FLAGS...: `pointseg segment params.json FLAGS --output
# labels` with --server answers what it answers locally.
same_as_local() {
    name=$1
    shift
    if ! "$PS" segment "$tmp/params.json" "$@" --output labels >"$tmp/local.labels" 2>"$tmp/e"; then
        fail "$name" "local segment: $(head -c 200 "$tmp/e")"
        return
    fi
    check "$name" "$PS" segment "$tmp/params.json" --server "$plain" "$@" --output labels &&
        same_labels "$name" "$tmp/$name.out"
}
same_as_local cli-server-json-params
same_as_local cli-server-flag-over-json --k 10 --ncut_threshold 0.1
same_as_local cli-server-flag-twice --output json
# The Python command line drops a JSON input's "params" that a --param
# overrides, as pointseg does (the daemon answered the pair with a 400).
if "$PS" segment "$tmp/params.json" --k 10 --ncut_threshold 0.1 --output labels >"$tmp/local.labels" 2>"$tmp/e"
then
    check python-param-over-json python3 "$py" segment "$tmp/params.json" --server "$plain" \
        --param k=10 --param ncut-threshold=0.1 --output labels &&
        same_labels python-param-over-json "$tmp/python-param-over-json.out"
else fail python-param-over-json "local segment: $(head -c 200 "$tmp/e")"; fi
"$PS" segment "$SAMPLE" --server "$secured" >/dev/null 2>"$tmp/e"
rc=$?
if [ "$rc" -eq 2 ] && grep -q 'answered 401' "$tmp/e"; then pass cli-server-no-token
else fail cli-server-no-token "exit status $rc: $(head -c 200 "$tmp/e")"; fi
"$PS" segment "$tmp/bad.xyz" --server "$plain" --async >/dev/null 2>"$tmp/e"
rc=$?
if [ "$rc" -eq 2 ] && grep -q 'answered 4' "$tmp/e"; then pass cli-server-bad-input
else fail cli-server-bad-input "exit status $rc: $(head -c 200 "$tmp/e")"; fi

# wrong_answer NAME MODE PATTERN: `pointseg segment --server --async` on the
# stand-in's MODE exits 1 (a bad server answer) within 10 s, PATTERN on
# stderr.
wrong_answer() {
    timeout 10 "$PS" segment "$SAMPLE" --server "$wrong/$2" --async >/dev/null 2>"$tmp/e"
    rc=$?
    if [ "$rc" -eq 1 ] && grep -q "$3" "$tmp/e"; then pass "$1"
    else fail "$1" "exit status $rc: $(head -c 200 "$tmp/e")"; fi
}
wrong_answer cli-server-no-job-id no-id "answered 202 without a readable job id"
wrong_answer cli-server-bad-status bad-status "without a readable status"

[ "$failures" -eq 0 ]
