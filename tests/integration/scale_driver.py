"""scale_driver.py: the body of tests/integration/scale.sh (make test-scale).

    python3 scale_driver.py BUILD TMP NGINX NGINX_CONF_TEMPLATE [SUITE]

Starts redis-server (append-only file on, as in docker/compose.yaml), three
pointsegd --redis on loopback and nginx with the template's "server
pointsegd:8080" line turned into the three replicas; then:
  mixed          300 requests through nginx with 8 clients: sync and async,
                 valid and invalid, cancels; every answer checked (labels
                 against a local run, statuses, problem+json)
  any-replica    a job posted to one replica read (status, result) from each
                 of the others
  sigkill        a replica is SIGKILLed while it runs a job: the job finishes
                 on another (polled through nginx), same labels
  three-losses   a job whose replica is SIGKILLed three times fails, saying so
  redis-restart  redis-server stops mid-run: 503s with Retry-After, no crash;
                 it comes back: the daemons recover, jobs from before and
                 after it finish
  no-job-lost    every accepted job ended done (or cancelled when asked)
  no-sanitizer-report  no replica's log reports a sanitizer finding (for a
                 BUILD made with SAN=1 or TSAN=1)
Prints PASS/FAIL lines named SUITE:check (SUITE "scale" unless given); the
shell counts them.
"""
import concurrent.futures
import os
import re
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from http_checks import (SUITE, call, free_port, inputs, metric, no_job_lost, poll, report,  # noqa: E402
                         result_labels, submit, wait_http)

BUILD, TMP, NGINX, TEMPLATE = sys.argv[1:5]
if len(sys.argv) > 5:
    SUITE[0] = sys.argv[5]
PS, PSD = BUILD + "/pointseg", BUILD + "/pointsegd"
LEASE = 3
# What an AddressSanitizer, UBSan or ThreadSanitizer build prints on a finding.
SANITIZER_REPORT = re.compile(r"^(==\d+==ERROR: \w+Sanitizer|WARNING: ThreadSanitizer|.*: runtime error: )", re.M)
procs = []
accepted = {}  # job id -> (expected labels or None when cancelled, what)


class Redis:
    def __init__(self):
        self.port = free_port()
        self.dir = os.path.join(TMP, "redis")
        os.makedirs(self.dir, exist_ok=True)
        self.proc = None

    def start(self):
        self.proc = subprocess.Popen(
            ["redis-server", "--port", str(self.port), "--bind", "127.0.0.1", "--dir", self.dir,
             "--appendonly", "yes", "--save", "", "--logfile", os.path.join(self.dir, "log")])
        procs.append(self.proc)
        end = time.monotonic() + 10
        while time.monotonic() < end:
            if self.cli("PING") == "PONG":
                return True
            time.sleep(0.1)
        return False

    def stop(self):
        self.proc.terminate()
        self.proc.wait(10)

    def cli(self, *args):
        r = subprocess.run(["redis-cli", "-p", str(self.port)] + list(args),
                           capture_output=True, text=True)
        return r.stdout.strip()


class Replica:
    def __init__(self, n, redis_url):
        self.n, self.port, self.url = n, free_port(), redis_url
        self.base = "http://127.0.0.1:%d" % self.port
        self.proc = None

    def start(self):
        log = open(os.path.join(TMP, "replica-%d.log" % self.n), "a")
        self.proc = subprocess.Popen(
            [PSD, "--port", str(self.port), "--threads", "1", "--redis", self.url,
             "--job-lease", str(LEASE), "--drain-seconds", "5",
             "--max-connections-per-ip", "0"],  # as in compose.yaml: nginx limits per client
            stdout=log, stderr=log)
        procs.append(self.proc)
        return wait_http(self.base)


def start_nginx(replicas):
    port = free_port()
    for d in ("body", "proxy", "fastcgi", "uwsgi", "scgi"):
        os.makedirs(os.path.join(TMP, d), exist_ok=True)
    servers = "\n        ".join("server 127.0.0.1:%d max_fails=1 fail_timeout=5s;" % r.port
                                 for r in replicas)
    conf = open(TEMPLATE).read()
    temp = "".join("    %s_temp_path %s/%s;\n" % (d if d != "body" else "client_body", TMP, d)
                   for d in ("body", "proxy", "fastcgi", "uwsgi", "scgi"))
    conf = re.sub(r"^ *server pointsegd:8080[^;\n]*;", "        " + servers, conf, flags=re.M)
    conf = conf.replace("listen 8080;", "listen 127.0.0.1:%d;" % port)
    conf = conf.replace("access_log /dev/stdout;", "access_log %s/access.log;" % TMP)
    conf = conf.replace("error_log /dev/stderr warn;", "error_log %s/error.log warn;" % TMP)
    conf = conf.replace("http {\n", "http {\n" + temp, 1)
    path = os.path.join(TMP, "nginx.conf")
    open(path, "w").write(conf)
    globals_ = "pid %s/nginx.pid; error_log %s/error.log;" % (TMP, TMP)
    t = subprocess.run([NGINX, "-t", "-p", TMP, "-c", path, "-g", globals_],
                       capture_output=True, text=True)
    if not report(t.returncode == 0, "nginx-t", t.stderr[-400:]):
        return None
    procs.append(subprocess.Popen([NGINX, "-p", TMP, "-c", path, "-g", globals_ + " daemon off;"],
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
    base = "http://127.0.0.1:%d" % port
    return base if wait_http(base) else None


# ---- phases -----------------------------------------------------------------

def mixed(base, small, small_labels, medium):
    deadline = time.monotonic() + 150

    def sync_ok(_):
        status, raw, _h = call(base, "POST", "/segment?output=labels", small)
        if status != 200 or raw.decode().split() != small_labels:
            return "POST /segment: %d %.80r" % (status, raw)

    def async_ok(_):
        status, job, _h = submit(base, small)
        if status != 202:
            return "POST /jobs: %d %.80r" % (status, job)
        accepted[job] = (small_labels, "mixed")
        state, err = poll(base, job, deadline)
        if state != "done":
            return "job %s: %s %s" % (job, state, err)
        if result_labels(base, job) != small_labels:
            return "job %s: labels differ from the local run" % job

    def invalid(i):
        kind = i % 3
        if kind == 0:
            status, raw, h = call(base, "POST", "/jobs", b"ply\nformat nonsense\n")
            want = 400
        elif kind == 1:
            status, raw, h = call(base, "POST", "/jobs?frobnicate=1", small)
            want = 400
        else:
            status, raw, h = call(base, "GET", "/jobs/00000000000000000000000000000000")
            want = 404
        if status != want or "problem+json" not in h.get("Content-Type", ""):
            return "invalid request %d answered %d %s" % (kind, status, h.get("Content-Type"))

    def cancel(_):
        status, job, _h = submit(base, medium, "output=labels&centrality=exact")
        if status != 202:
            return "POST /jobs (to cancel): %d" % status
        accepted[job] = (None, "cancelled")
        status, raw, _h = call(base, "DELETE", "/jobs/" + job)
        if status != 202:
            return "DELETE /jobs/%s: %d %.80r" % (job, status, raw)
        state, err = poll(base, job, deadline)
        if state != "cancelled":
            return "cancelled job %s ended %s %s" % (job, state, err)
        status, raw, _h = call(base, "GET", "/jobs/%s/result" % job)
        if status != 409:
            return "result of cancelled job %s: %d" % (job, status)

    kinds = [sync_ok, async_ok, sync_ok, async_ok, invalid, sync_ok, async_ok, invalid, async_ok, cancel]
    with concurrent.futures.ThreadPoolExecutor(8) as pool:
        work = [pool.submit(kinds[i % len(kinds)], i) for i in range(300)]
        errors = []
        for w in work:
            try:
                e = w.result()
            except Exception as x:  # a transport error is a wrong answer too
                e = "%s: %s" % (type(x).__name__, x)
            if e:
                errors.append(e)
    report(not errors, "mixed-300", "%d of 300 wrong, first: %s" % (len(errors), errors[:2]))


def any_replica(replicas, small, small_labels):
    status, job, _h = submit(replicas[0].base, small)
    if not report(status == 202, "any-replica-submit", "POST /jobs answered %d" % status):
        return
    accepted[job] = (small_labels, "any-replica")
    bad = []
    for r in replicas[1:]:
        state, err = poll(r.base, job, time.monotonic() + 60)
        if state != "done" or result_labels(r.base, job) != small_labels:
            bad.append("replica %d: %s %s" % (r.n, state, err))
    report(not bad, "any-replica-reads", "; ".join(bad))


def sigkill(base, replicas, redis, medium, medium_labels):
    status, job, _h = submit(base, medium, "output=labels&centrality=exact")
    if not report(status == 202, "sigkill-submit", "POST /jobs answered %d" % status):
        return
    accepted[job] = (medium_labels, "sigkill")
    state, err = poll(base, job, time.monotonic() + 60, ("running", "done", "failed", "cancelled"))
    worker = redis.cli("HGET", "pointseg:job:" + job, "worker")
    victim = next((r for r in replicas if r.proc and "-%d-" % r.proc.pid in worker), None)
    if not report(state == "running" and victim is not None, "sigkill-running",
                  "job %s: %s, worker %r" % (job, state, worker)):
        return
    victim.proc.send_signal(signal.SIGKILL)
    victim.proc.wait()
    t0 = time.monotonic()
    state, err = poll(base, job, time.monotonic() + 120)
    took = time.monotonic() - t0
    labels = result_labels(base, job) if state == "done" else None
    report(state == "done" and labels == medium_labels, "sigkill-job-finishes-elsewhere",
           "job %s: %s %s, labels %s" % (job, state, err, "same" if labels == medium_labels else "differ"))
    print("scale: job finished %.1f s after its replica was killed" % took, file=sys.stderr)
    survivors = [r for r in replicas if r is not victim]
    reclaimed = sum(metric(r.base, "pointseg_jobs_reclaimed_total") or 0 for r in survivors)
    report(reclaimed >= 1, "sigkill-reclaimed-metric", "reclaimed total %s" % reclaimed)
    report(victim.start(), "sigkill-replica-restarts", "replica %d did not come back" % victim.n)


def runner_of(replicas, redis, job, previous, deadline):
    """The replica running job, once a worker other than previous holds it."""
    while time.monotonic() < deadline:
        worker = redis.cli("HGET", "pointseg:job:" + job, "worker")
        state = redis.cli("HGET", "pointseg:job:" + job, "state")
        if state != "running" and state != "queued":
            return None
        if state == "running" and worker != previous:
            for r in replicas:
                if r.proc and r.proc.poll() is None and "-%d-" % r.proc.pid in worker:
                    return r, worker
        time.sleep(0.05)
    return None


def three_losses(base, replicas, redis, medium):
    """A job whose replica is SIGKILLed three times fails, saying so."""
    status, job, _h = submit(base, medium, "output=labels&centrality=exact")
    if not report(status == 202, "three-losses-submit", "POST /jobs answered %d" % status):
        return
    previous, kills = None, 0
    for _ in range(3):
        found = runner_of(replicas, redis, job, previous, time.monotonic() + 60)
        if not found:
            break
        victim, previous = found
        victim.proc.send_signal(signal.SIGKILL)
        victim.proc.wait()
        kills += 1
        victim.start()
    state, err = poll(base, job, time.monotonic() + 60)
    detail = (err or {}).get("detail", "")
    report(kills == 3 and state == "failed" and "lost its worker 3 times" in detail, "three-losses-fail",
           "%d kills, job %s, error %r" % (kills, state, detail))


def redis_restart(base, replicas, redis, small, small_labels):
    before = [submit(base, small) for _ in range(6)]
    ids = [job for status, job, _h in before if status == 202]
    for job in ids:
        accepted[job] = (small_labels, "before-restart")
    time.sleep(1.2)  # the append-only file is written every second
    redis.stop()
    status, raw, headers = call(base, "POST", "/jobs?output=labels", small)
    report(status == 503 and headers.get("Retry-After") and b"unreachable" in raw, "redis-down-post-503",
           "POST /jobs answered %d %s %.100r" % (status, headers.get("Retry-After"), raw))
    ready = [call(r.base, "GET", "/readyz")[0] for r in replicas]
    report(ready == [503] * 3, "redis-down-readyz-503", "readyz %s" % ready)
    status, raw, _h = call(base, "GET", "/jobs/" + (ids[0] if ids else "x"))
    report(status == 503, "redis-down-job-read-503", "GET /jobs/{id} answered %d" % status)
    status, raw, _h = call(base, "POST", "/segment?output=labels", small)
    report(status == 200 and raw.decode().split() == small_labels, "redis-down-segment-works",
           "POST /segment answered %d" % status)
    alive = [r.proc.poll() is None for r in replicas]
    report(all(alive), "redis-down-no-crash", "replicas alive %s" % alive)
    report(redis.start(), "redis-back", "redis-server did not restart")
    back = all(wait_http(r.base, "/readyz", 15) for r in replicas)
    report(back, "redis-back-readyz", "a replica stayed unready")
    after = [submit(base, small) for _ in range(6)]
    bad = [status for status, job, _h in after if status != 202]
    for status, job, _h in after:
        if status == 202:
            accepted[job] = (small_labels, "after-restart")
    report(not bad, "redis-back-post", "POST /jobs answered %s" % bad)


def main():
    small, small_labels, medium, medium_labels = inputs(TMP, PS)
    redis = Redis()
    if not report(redis.start(), "redis-start", "redis-server did not answer"):
        return
    url = "redis://127.0.0.1:%d" % redis.port
    replicas = [Replica(n, url) for n in (1, 2, 3)]
    if not report(all(r.start() for r in replicas), "replicas-start", "a replica did not start"):
        return
    base = start_nginx(replicas)
    if not report(base is not None, "nginx-start", "nginx did not answer"):
        return
    mixed(base, small, small_labels, medium)
    any_replica(replicas, small, small_labels)
    sigkill(base, replicas, redis, medium, medium_labels)
    three_losses(base, replicas, redis, medium)
    redis_restart(base, replicas, redis, small, small_labels)
    no_job_lost(base, accepted)
    logs = [open(os.path.join(TMP, "replica-%d.log" % r.n)).read() for r in replicas]
    served = [len(re.findall(r"^POST /(?:segment 200|jobs 202) ", log, re.M)) for log in logs]
    report(all(served), "every-replica-served", "requests per replica %s" % served)


def no_sanitizer_report():
    """Run however the checks ended, after the replicas' shutdown (a race
    in it counts too), so that a replica a sanitizer stopped is named even
    when the checks above could not finish."""
    findings = []
    for name in sorted(os.listdir(TMP)):
        if re.fullmatch(r"replica-\d+\.log", name):
            with open(os.path.join(TMP, name), errors="replace") as f:
                log = f.read()
            found = SANITIZER_REPORT.search(log)
            if found:
                summary = re.search(r"^SUMMARY: .*", log, re.M)
                findings.append("%s: %s" % (name, (summary or found).group(0).strip()))
    report(not findings, "no-sanitizer-report", "; ".join(findings))


try:
    main()
finally:
    for p in procs:
        if p.poll() is None:
            p.terminate()
    for p in procs:
        try:
            p.wait(10)
        except subprocess.TimeoutExpired:
            p.kill()
    no_sanitizer_report()
