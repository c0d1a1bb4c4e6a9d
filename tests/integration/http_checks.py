"""http_checks.py: what the Python test drivers share (scale_driver.py here,
tests/docker/compose_driver.py): PASS/FAIL lines, free ports, the sphere
test input, HTTP calls with their status, and the job helpers (submit,
poll to a final state, result labels, a metric's value), the test inputs and
the closing check that no accepted job was lost."""
import json
import math
import os
import re
import socket
import subprocess
import time
import urllib.error
import urllib.request


SUITE = ["scale"]


def report(ok, name, why=""):
    suite = SUITE[0]
    print(("PASS %s:%s" % (suite, name)) if ok else ("FAIL %s:%s: %s" % (suite, name, why)), flush=True)
    return ok


def free_port():
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


def sphere(m, shift=0.0):
    golden = 3.141592653589793 * (3 - 5 ** 0.5)
    rows = []
    for i in range(m):
        y = 1 - 2 * (i + 0.5) / m
        r = (1 - y * y) ** 0.5
        t = golden * i
        rows.append("%.6f %.6f %.6f" % (shift + r * math.cos(t), y, r * math.sin(t)))
    return rows


def write(tmp, name, rows):
    path = os.path.join(tmp, name)
    with open(path, "w") as f:
        f.write("\n".join(rows) + "\n")
    return path


def call(base, method, path, data=None, timeout=30):
    req = urllib.request.Request(base + path, data=data, method=method)
    if data is not None:
        req.add_header("Content-Type", "application/octet-stream")
    try:
        with urllib.request.urlopen(req, timeout=timeout) as r:
            return r.status, r.read(), dict(r.headers)
    except urllib.error.HTTPError as e:
        return e.code, e.read(), dict(e.headers)


def wait_http(base, path="/healthz", seconds=10, want=200):
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        try:
            if call(base, "GET", path, timeout=2)[0] == want:
                return True
        except OSError:
            pass
        time.sleep(0.1)
    return False


def poll(base, job, deadline, states=("done", "failed", "cancelled")):
    """Polls GET /jobs/{id} until a final state; (state, error) or (None, why)."""
    while time.monotonic() < deadline:
        try:
            status, raw, _ = call(base, "GET", "/jobs/" + job)
        except OSError as e:
            return None, "GET /jobs/%s: %s" % (job, e)
        if status == 503:
            time.sleep(0.2)
            continue
        if status != 200:
            return None, "GET /jobs/%s answered %d (job lost)" % (job, status)
        doc = json.loads(raw)
        if doc["status"] in states:
            return doc["status"], doc.get("error")
        time.sleep(0.05)
    return None, "job %s not final at the deadline" % job


def result_labels(base, job):
    status, raw, _ = call(base, "GET", "/jobs/%s/result" % job)
    return raw.decode().split() if status == 200 else None


def submit(base, body, query="output=labels"):
    status, raw, headers = call(base, "POST", "/jobs?" + query, body)
    return status, (json.loads(raw).get("id") if status == 202 else raw), headers


def metric(base, name):
    status, raw, _h = call(base, "GET", "/metrics")
    m = re.search(r"^%s (\S+)$" % name, raw.decode(), re.M) if status == 200 else None
    return float(m.group(1)) if m else None


def local_labels(ps, path, *params):
    """The labels `pointseg segment` gives locally."""
    out = subprocess.run([ps, "segment", path, "--output", "labels"] + list(params),
                         check=True, capture_output=True, text=True).stdout
    return out.split()


def inputs(tmp, ps):
    """(small body, its labels, medium body, its labels with exact centrality):
    two spheres of 150 points (quick, two segments) and a sphere of 6000
    points, seconds of work with centrality=exact."""
    small_path = write(tmp, "small.xyz", sphere(150) + sphere(150, 4.0))
    medium_path = write(tmp, "medium.xyz", sphere(6000))
    return (open(small_path, "rb").read(), local_labels(ps, small_path),
            open(medium_path, "rb").read(),
            local_labels(ps, medium_path, "--centrality", "exact", "--threads", "1"))


def no_job_lost(base, accepted, name="no-job-lost"):
    """Every accepted job (id -> (labels, or None when it was cancelled;
    what)) ends as expected."""
    bad = []
    deadline = time.monotonic() + 120
    for job, (labels, what) in accepted.items():
        state, err = poll(base, job, deadline)
        if labels is None:
            ok = state == "cancelled"
        else:
            ok = state == "done" and result_labels(base, job) == labels
        if not ok:
            bad.append("%s job %s: %s %s" % (what, job, state, err))
    report(not bad, name, "%d of %d: %s" % (len(bad), len(accepted), bad[:3]))
