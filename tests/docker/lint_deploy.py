"""lint_deploy.py: the deployment files read against the daemon they run.

    python3 lint_deploy.py ROOT POINTSEGD

Needs no Docker (tests/docker/run.sh runs it first).  Checks: every
--flag and POINTSEG_* variable that docker/Dockerfile, compose.yaml,
k8s/*.yaml and pointsegd.service give is one `pointsegd --help` lists; every
k8s probe (httpGet) names a port the container listens on and a path the
daemon answers 200; the Dockerfile's HEALTHCHECK, run beside pointsegd
started as the image starts it, finds the daemon wherever docker run's
flags or -e tell it to listen (another port, 127.0.0.2, this machine's own
non-loopback address: a SKIP line when `hostname -I` has none) and says
unhealthy once it is gone; a
Deployment whose image is `:latest` (or untagged) sets imagePullPolicy, since
Kubernetes would otherwise pull it on every start (Always) and never use an
image loaded into the cluster (kind load, minikube image load); a
Deployment's pointsegd has a preStop sleep (at SIGTERM it stops taking work
at once, so without one the Service still routes requests to it for a
moment) and a terminationGracePeriodSeconds longer than that sleep, its
--drain-seconds and the 5 s the daemon then waits for its last answers.
Prints PASS/FAIL/SKIP lines.
"""
import glob
import ipaddress
import json
import os
import re
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "integration"))
from http_checks import SUITE, call, free_port, report, wait_http  # noqa: E402

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

# The k8s probes: (file, port, path), the port as the container's (the
# HEALTHCHECK is run below).
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
                code = call("http://127.0.0.1:%d" % port, "GET", path, timeout=5)[0]
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


# The HEALTHCHECK run as Docker runs it, beside pointsegd started as the
# image starts it: its ENTRYPOINT, then its CMD or `docker run IMAGE ARGS`'s
# ARGS, with its ENV under docker run's -e.  The check must find the daemon
# where it was told to listen (--bind or POINTSEG_BIND, --port or
# POINTSEG_PORT; a flag wins, as in pointsegd) and say unhealthy (1) once
# it is gone.  The check's command gets the daemon's pid as its argument:
# in the container the daemon is PID 1.
def final_stage(text):
    """The Dockerfile's last stage, continuation lines joined:
    {INSTRUCTION: [its arguments, one a line]}."""
    stage = re.sub(r"\\\n\s*", " ", text).split("\nFROM ")[-1]
    out = {}
    for line in stage.splitlines():
        word, _, rest = line.strip().partition(" ")
        if word.isupper():
            out.setdefault(word, []).append(rest.strip())
    return out


STAGE = final_stage(dockerfile)
IMAGE_ENV = dict(re.findall(r"(POINTSEG_[A-Z0-9_]+)=(\S+)", " ".join(STAGE.get("ENV", []))))
# Where COPY puts each file of the checkout in the image.
INSTALLED = {}
for copy in STAGE.get("COPY", []):
    words = copy.split()
    if not words[0].startswith("--from"):
        src, dest = words[-2:]
        INSTALLED[dest + os.path.basename(src) if dest.endswith("/") else dest] = os.path.join(ROOT, src)


def health_command(pid):
    """The HEALTHCHECK's CMD, run from the checkout, pid its argument."""
    text = STAGE["HEALTHCHECK"][0].partition(" CMD ")[2].strip()
    if not text.startswith("["):
        return ["/bin/sh", "-c", text, "sh", str(pid)]
    argv = json.loads(text)
    for dest, src in INSTALLED.items():
        if argv[0] in (dest, os.path.basename(dest)):
            argv[0] = src
    return argv + [str(pid)]


def health_status(pid, env):
    try:
        return subprocess.run(health_command(pid), env=env, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL, timeout=10).returncode
    except subprocess.TimeoutExpired:
        return "a timeout"


def answers_now(host, port):
    """True when something answers HTTP at host:port at once."""
    try:
        call("http://%s:%d" % (host, port), "GET", "/healthz", timeout=2)
        return True
    except OSError:
        return False


def local_address():
    """An IPv4 address of this machine other than loopback, or None."""
    try:
        found = subprocess.run(["hostname", "-I"], capture_output=True, text=True).stdout.split()
    except OSError:
        return None
    for a in found:
        ip = ipaddress.ip_address(a)
        if ip.version == 4 and not ip.is_loopback:
            return a
    return None


def check_health(name, args, extra_env, host, port, while_up=None):
    """pointsegd started as `docker run [-e extra_env] IMAGE [args]` (args None:
    the CMD) must listen on host:port and the HEALTHCHECK say healthy (0);
    while_up() runs before the daemon is stopped.  Returns the daemon's
    environment and pid, or None when either failed."""
    env = {k: v for k, v in os.environ.items() if not k.startswith("POINTSEG_")}
    env.update(IMAGE_ENV)
    env.update(extra_env)
    entry = json.loads(STAGE["ENTRYPOINT"][0])
    cmd = json.loads(STAGE["CMD"][0]) if "CMD" in STAGE else []
    daemon = subprocess.Popen([PSD] + entry[1:] + (cmd if args is None else args), env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        up = wait_http("http://%s:%d" % (host, port), seconds=5)
        status = health_status(daemon.pid, env) if up else None
        report(up and status == 0, "healthcheck-" + name,
               "exit status %s, not 0 (healthy)" % status if up
               else "pointsegd does not answer on %s:%d" % (host, port))
        if up and while_up:
            while_up()
    finally:
        daemon.terminate()
        daemon.wait()
    return (env, daemon.pid) if up and status == 0 else None


port = free_port()
check_health("bind-flag-loopback", ["--bind", "127.0.0.2", "--port", str(port)], {}, "127.0.0.2", port)
port = free_port()
ran = check_health("follows-port", None, {"POINTSEG_PORT": str(port)}, "127.0.0.1", port)
if ran:
    status = health_status(ran[1], ran[0])
    report(status == 1, "healthcheck-unhealthy-when-down", "exit status %s, not 1 (unhealthy)" % status)
address = local_address()
if address:
    # Told by the environment, the daemon listens there only (a --bind in
    # the CMD would win over docker run's -e POINTSEG_BIND).
    port = free_port()
    check_health("bind-env", None, {"POINTSEG_BIND": address, "POINTSEG_PORT": str(port)}, address, port,
                 lambda: report(not answers_now("127.0.0.1", port), "dockerfile-bind-env-honoured",
                                "-e POINTSEG_BIND=%s: pointsegd answers on 127.0.0.1 too" % address))
    port = free_port()
    check_health("bind-flag", ["--bind=" + address, "--port=%d" % port], {}, address, port)
else:
    print("SKIP docker:healthcheck-non-loopback: no IPv4 address other than loopback in `hostname -I`: "
          "the check was not run against a daemon on another address", flush=True)
