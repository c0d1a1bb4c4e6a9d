"""compose_driver.py: the checks tests/docker/run.sh runs on the compose
topology (redis + 3 pointsegd + nginx, in Docker).

    python3 compose_driver.py PROJECT COMPOSE_ARGS... -- BASE TMP PS

BASE is nginx's published address.  Checks, as make test-scale does on
loopback: sync and async requests through nginx with the labels of a local
run; a job posted through nginx read from inside every replica; a replica
`docker kill`ed while it runs a job (the job finishes on another); Redis
`docker kill`ed and started again (503s meanwhile, recovery after); a
fourth replica added as compose.yaml says (up --scale, nginx reloaded) takes
jobs through nginx; no job lost.  Prints PASS/FAIL lines.
"""
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "integration"))
from http_checks import (SUITE, call, inputs, no_job_lost, poll, report, result_labels,  # noqa: E402
                         submit)

SUITE[0] = "docker"
sep = sys.argv.index("--")
COMPOSE = ["docker-compose", "-p", sys.argv[1]] + sys.argv[2:sep]
BASE, TMP, PS = sys.argv[sep + 1:sep + 4]
accepted = {}


def compose(*args):
    return subprocess.run(COMPOSE + list(args), capture_output=True, text=True).stdout.strip()


def containers(service):
    return compose("ps", "-q", service).split()


def docker(*args):
    return subprocess.run(["docker"] + list(args), capture_output=True, text=True)


def inside(cid, path):
    """GET path on the replica in container cid (its own curl)."""
    r = docker("exec", cid, "curl", "-s", "-w", "\n%{http_code}", "http://127.0.0.1:8080" + path)
    body, _, code = r.stdout.rpartition("\n")
    return (int(code) if code.isdigit() else 0), body


def redis_cli(*args):
    cid = containers("redis")
    return docker("exec", cid[0], "redis-cli", *args).stdout.strip() if cid else ""


def sync_and_async(small, labels):
    status, raw, _h = call(BASE, "POST", "/segment?output=labels", small)
    report(status == 200 and raw.decode().split() == labels, "compose-segment", "answered %d" % status)
    ok = True
    for _ in range(6):
        status, job, _h = submit(BASE, small)
        ok = ok and status == 202
        if status == 202:
            accepted[job] = (labels, "compose")
    report(ok, "compose-jobs-accepted", "a POST /jobs was refused")


def every_replica_reads(small, labels):
    status, job, _h = submit(BASE, small)
    if not report(status == 202, "compose-any-replica-submit", "answered %d" % status):
        return
    accepted[job] = (labels, "compose")
    poll(BASE, job, time.monotonic() + 60)
    replicas = containers("pointsegd")
    seen = [inside(cid, "/jobs/%s/result" % job) for cid in replicas]
    good = [code == 200 and body.split() == labels for code, body in seen]
    report(len(replicas) == 3 and all(good), "compose-every-replica-reads",
           "%d replicas, answers %s" % (len(replicas), [code for code, _ in seen]))


def kill_running_replica(medium, labels):
    status, job, _h = submit(BASE, medium, "output=labels&centrality=exact")
    if not report(status == 202, "compose-kill-submit", "answered %d" % status):
        return
    accepted[job] = (labels, "compose")
    state, _err = poll(BASE, job, time.monotonic() + 60, ("running", "done", "failed", "cancelled"))
    worker = redis_cli("HGET", "pointseg:job:" + job, "worker")
    victim = next((cid for cid in containers("pointsegd") if cid[:12] in worker), None)
    if not report(state == "running" and victim, "compose-kill-running", "%s on %r" % (state, worker)):
        return
    docker("kill", victim)
    state, err = poll(BASE, job, time.monotonic() + 120)
    report(state == "done" and result_labels(BASE, job) == labels, "compose-killed-job-finishes",
           "job %s: %s %s" % (job, state, err))
    docker("start", victim)


def kill_redis(small, labels):
    cid = containers("redis")[0]
    time.sleep(1.2)  # the append-only file is written every second
    docker("kill", cid)
    status, raw, headers = call(BASE, "POST", "/jobs?output=labels", small)
    report(status == 503 and "Retry-After" in headers, "compose-redis-down-503", "answered %d" % status)
    status, raw, _h = call(BASE, "POST", "/segment?output=labels", small)
    report(status == 200, "compose-redis-down-segment", "answered %d" % status)
    docker("start", cid)
    replicas = containers("pointsegd")
    end = time.monotonic() + 60
    while time.monotonic() < end and any(inside(r, "/readyz")[0] != 200 for r in replicas):
        time.sleep(0.5)
    ready = [inside(r, "/readyz")[0] for r in replicas]
    report(ready == [200] * len(replicas), "compose-redis-back", "replicas' /readyz %s" % ready)
    status, job, _h = submit(BASE, small)
    if report(status == 202, "compose-redis-back-post", "answered %d %.200r" % (status, job)):
        accepted[job] = (labels, "compose")


def scale_up(small, labels):
    """compose.yaml's way to add a replica: up --scale, then reload nginx
    (it looks "pointsegd" up only when it loads its configuration)."""
    os.environ["PUBLISH"] = BASE.split("//", 1)[1]  # as run.sh's up, or nginx is recreated
    before = set(containers("pointsegd"))
    compose("up", "-d", "--no-build", "--scale", "pointsegd=4")
    added = [cid for cid in containers("pointsegd") if cid not in before]
    end = time.monotonic() + 60
    while added and time.monotonic() < end and inside(added[0], "/readyz")[0] != 200:
        time.sleep(0.5)
    compose("exec", "-T", "nginx", "nginx", "-s", "reload")
    time.sleep(1)
    for _ in range(8):
        status, job, _h = submit(BASE, small)
        if status == 202:
            accepted[job] = (labels, "compose")
    log = docker("logs", added[0]) if added else None
    served = (log.stdout + log.stderr).count("POST /jobs 202") if log else 0
    report(len(added) == 1 and served > 0, "compose-scale-up-served",
           "%d replicas added; the new one took %d of 8 jobs posted through nginx" % (len(added), served))


def main():
    small, small_labels, medium, medium_labels = inputs(TMP, PS)
    sync_and_async(small, small_labels)
    every_replica_reads(small, small_labels)
    kill_running_replica(medium, medium_labels)
    kill_redis(small, small_labels)
    scale_up(small, small_labels)
    no_job_lost(BASE, accepted, "compose-no-job-lost")


main()
