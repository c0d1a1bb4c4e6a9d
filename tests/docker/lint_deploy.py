"""lint_deploy.py: the deployment files read against the daemon they run.

    python3 lint_deploy.py ROOT POINTSEGD

Needs no Docker (tests/docker/run.sh runs it first).  Checks: every
--flag and POINTSEG_* variable that docker/Dockerfile, compose.yaml,
k8s/*.yaml and pointsegd.service give is one `pointsegd --help` lists; every
probe and health check (k8s httpGet, the Dockerfile's HEALTHCHECK) names a
port the container listens on (the HEALTHCHECK's: ${POINTSEG_PORT:-N}, N
the Dockerfile's POINTSEG_PORT) and a path the daemon answers 200; a
Deployment whose image is `:latest` (or untagged) sets imagePullPolicy, since
Kubernetes would otherwise pull it on every start (Always) and never use an
image loaded into the cluster (kind load, minikube image load); a
Deployment's pointsegd has a preStop sleep (at SIGTERM it stops taking work
at once, so without one the Service still routes requests to it for a
moment) and a terminationGracePeriodSeconds longer than that sleep, its
--drain-seconds and the 5 s the daemon then waits for its last answers.
Prints PASS/FAIL lines.
"""
import glob
import os
import re
import subprocess
import sys
import time
import urllib.request

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "integration"))
from http_checks import SUITE, free_port, report  # noqa: E402

import yaml  # noqa: E402  (python3-yaml, a dependency of docker-compose)

SUITE[0] = "docker"
ROOT, PSD = sys.argv[1], sys.argv[2]
DOCKER = os.path.join(ROOT, "docker")

help_text = subprocess.run([PSD, "--help"], capture_output=True, text=True).stdout
FLAGS = set(re.findall(r"^\s+(--[a-z0-9-]+)", help_text, re.M))
ENVS = set(re.findall(r"\b(POINTSEG_[A-Z0-9_]+)\b", help_text))


def docs(path):
    with open(path) as f:
        return [d for d in yaml.safe_load_all(f) if d]


def pod_containers(doc):
    spec = doc.get("spec", {}).get("template", {}).get("spec", {})
    return spec.get("containers", [])


k8s = {os.path.basename(p): docs(p) for p in sorted(glob.glob(os.path.join(DOCKER, "k8s", "*.yaml")))}
compose = docs(os.path.join(DOCKER, "compose.yaml"))[0]
with open(os.path.join(DOCKER, "Dockerfile")) as f:
    dockerfile = f.read()
with open(os.path.join(DOCKER, "pointsegd.service")) as f:
    unit = f.read()

# What each file gives pointsegd: flags and variables.
flags, envs = [], []
for name, ds in k8s.items():
    for d in ds:
        for c in pod_containers(d):
            if "pointseg" not in c.get("image", ""):
                continue
            flags += [(name, a) for a in c.get("args", []) + c.get("command", []) if a.startswith("--")]
            envs += [(name, e["name"]) for e in c.get("env", [])]
svc = compose["services"]["pointsegd"]
envs += [("compose.yaml", e) for e in svc.get("environment", {})]
flags += [("compose.yaml", a) for a in svc.get("command", []) if a.startswith("--")]
envs += [("Dockerfile", e) for e in re.findall(r"\b(POINTSEG_[A-Z0-9_]+)=", dockerfile)]
flags += [("Dockerfile", a) for a in re.findall(r'"(--[a-z0-9-]+)"', dockerfile)]
envs += [("pointsegd.service", e) for e in re.findall(r"\b(POINTSEG_[A-Z0-9_]+)=", unit)]
flags += [("pointsegd.service", a) for a in re.findall(r"\s(--[a-z0-9-]+)", unit)]

unknown = ["%s: %s" % f for f in flags if f[1] not in FLAGS]
report(flags and not unknown, "deploy-flags-exist", "not in pointsegd --help: %s" % unknown)
unknown = ["%s: %s" % e for e in envs if e[1].startswith("POINTSEG_") and e[1] not in ENVS]
report(envs and not unknown, "deploy-env-exist", "not in pointsegd --help: %s" % unknown)

# Probes and health checks: (file, port, path), the port as the container's.
probes, bad_ports = [], []
for name, ds in k8s.items():
    for d in ds:
        for c in pod_containers(d):
            ports = {p.get("name"): p["containerPort"] for p in c.get("ports", [])}
            for kind in ("readinessProbe", "livenessProbe", "startupProbe"):
                get = c.get(kind, {}).get("httpGet")
                if not get:
                    continue
                port = ports.get(get["port"], get["port"])
                if port not in ports.values():
                    bad_ports.append("%s %s: port %s" % (name, kind, get["port"]))
                probes.append(("%s %s" % (name, kind), get["path"]))
                argv = c.get("args", [])
                if "--port" in argv and int(argv[argv.index("--port") + 1]) != port:
                    bad_ports.append("%s %s: port %s, daemon --port %s" %
                                     (name, kind, port, argv[argv.index("--port") + 1]))
# The HEALTHCHECK follows POINTSEG_PORT (docker run -e POINTSEG_PORT=...),
# with the Dockerfile's own value as its default.
checks = re.findall(r"HEALTHCHECK[^\n]*\n?[^\n]*http://127\.0\.0\.1:([^/\s\"]+)(/[^\s\"]*)", dockerfile)
if not checks:
    bad_ports.append("Dockerfile: no HEALTHCHECK on http://127.0.0.1:PORT/PATH")
for port, path in checks:
    probes.append(("Dockerfile HEALTHCHECK", path))
    default = re.fullmatch(r"\$\{POINTSEG_PORT:-(\d+)\}", port)
    if not default:
        bad_ports.append("Dockerfile HEALTHCHECK: port %s, not ${POINTSEG_PORT:-N}" % port)
    elif "POINTSEG_PORT=%s" % default.group(1) not in dockerfile:
        bad_ports.append("Dockerfile HEALTHCHECK: default port %s is not POINTSEG_PORT" % default.group(1))
report(probes and not bad_ports, "deploy-probe-ports", "; ".join(bad_ports) or "no probe found")

port = free_port()
daemon = subprocess.Popen([PSD, "--port", str(port), "--quiet"], stdout=subprocess.DEVNULL,
                          stderr=subprocess.DEVNULL)
try:
    answers = []
    for where, path in probes:
        code = 0
        for _ in range(50):
            try:
                code = urllib.request.urlopen("http://127.0.0.1:%d%s" % (port, path), timeout=5).status
                break
            except urllib.error.HTTPError as e:
                code = e.code
                break
            except OSError:
                time.sleep(0.1)
        answers.append((where, path, code))
    wrong = ["%s %s: %d" % a for a in answers if a[2] != 200]
    report(answers and not wrong, "deploy-probe-paths", "; ".join(wrong))
finally:
    daemon.terminate()
    daemon.wait()

# A :latest (or untagged) image without imagePullPolicy is pulled on every start.
latest = []
for name, ds in k8s.items():
    for d in ds:
        for c in pod_containers(d):
            image = c.get("image", "")
            tag = image.rsplit("/", 1)[-1].partition(":")[2]
            if tag in ("", "latest") and "imagePullPolicy" not in c:
                latest.append("%s: %s" % (name, image))
report(not latest, "k8s-latest-image-pull-policy",
       "image with tag latest and no imagePullPolicy (Kubernetes pulls it: Always): %s" % latest)

# preStop sleep + --drain-seconds + the last answers (main.c's ANSWER_SECONDS)
# within terminationGracePeriodSeconds (30 when not given).
def pre_stop_seconds(c):
    handler = c.get("lifecycle", {}).get("preStop", {})
    argv = handler.get("exec", {}).get("command", [])
    if len(argv) == 2 and argv[0] in ("sleep", "/bin/sleep"):
        return float(argv[1])
    return float(handler.get("sleep", {}).get("seconds", 0))


def drain_seconds(c):
    argv = c.get("args", []) + c.get("command", [])
    if "--drain-seconds" in argv:
        return float(argv[argv.index("--drain-seconds") + 1])
    env = {e["name"]: e.get("value") for e in c.get("env", [])}
    return float(env.get("POINTSEG_DRAIN_SECONDS", 30))


stops = []
for name, ds in k8s.items():
    for d in ds:
        if d.get("kind") != "Deployment":
            continue
        grace = d["spec"]["template"]["spec"].get("terminationGracePeriodSeconds", 30)
        for c in pod_containers(d):
            if "pointseg" not in c.get("image", ""):
                continue
            pre, drain = pre_stop_seconds(c), drain_seconds(c)
            if pre < 1:
                stops.append("%s: no preStop sleep" % name)
            if grace < pre + drain + 5:
                stops.append("%s: terminationGracePeriodSeconds %s < preStop %g + drain %g + 5"
                             % (name, grace, pre, drain))
report(stops == [] and any(d.get("kind") == "Deployment" for ds in k8s.values() for d in ds),
       "k8s-prestop-and-grace", "; ".join(stops) or "no Deployment found")
