#!/usr/bin/env python3
"""pointseg_client.py: a client of pointsegd, standard library only.

Command line:
    python3 pointseg_client.py segment FILE [--server URL] [--async]
        [--output json|labels|ply] [-o OUT] [--token TOKEN] [--param NAME=VALUE ...]

As with pointseg's flags, of a parameter given more than once (--param
ncut-threshold=... and ncut_threshold=... are one, --output is --param
output=...) the last is sent, and only it: the daemon refuses a second.
A parameter given here also drops its namesake from a JSON input's
"params".

As a module:
    import pointseg_client
    doc = pointseg_client.segment("scan.ply", server="http://127.0.0.1:8080", k=10)
    doc = pointseg_client.segment([[0, 0, 0], [1, 0, 0], ...], async_=True)

segment() returns the document: a dict for output="json" (see README), a list
of int labels for output="labels", the PLY bytes for output="ply".  Errors
from the daemon raise PointsegError with the HTTP status and the problem's
detail (also when the daemon answers before taking a large body, as it does
a 401); no answer (unreachable, connection closed, timeout) or an unreadable
job answer one with status 0.
"""

import argparse
import http.client
import json
import os
import sys
import time
import urllib.error
import urllib.parse
import urllib.request

DEFAULT_SERVER = os.environ.get("POINTSEG_SERVER", "http://127.0.0.1:8080")
FINAL_STATES = ("done", "failed", "cancelled")
OUTPUTS = ("json", "labels", "ply")
POLL_SECONDS = 0.2


class PointsegError(Exception):
    """An error answer from pointsegd (status 0: no answer at all)."""

    def __init__(self, status, detail):
        super().__init__("HTTP %d: %s" % (status, detail) if status else detail)
        self.status = status
        self.detail = detail


def _body_of(path_or_points):
    """The request body and its Content-Type for a path or a list of points."""
    if isinstance(path_or_points, (str, os.PathLike)):
        with open(path_or_points, "rb") as f:
            return f.read(), "application/octet-stream"
    points = [list(map(float, p)) for p in path_or_points]
    return json.dumps({"points": points}).encode(), "application/json"


def _spelt(name):
    """A parameter's name as the daemon takes it: '-' and '_' alike."""
    return name.replace("-", "_")


def _without_overridden(body, names):
    """A JSON object body without the members of its "params" that names
    (_spelt) override: those go in the query string, and the daemon
    refuses a parameter given twice.  Any other body as it is."""
    if not body.lstrip(b"\xef\xbb\xbf \t\r\n").startswith(b"{"):
        return body
    try:
        doc = json.loads(body)
    except ValueError:
        return body
    params = doc.get("params")
    if not isinstance(params, dict):
        return body
    kept = {k: v for k, v in params.items() if _spelt(k) not in names}
    if len(kept) == len(params):
        return body
    doc["params"] = kept
    return json.dumps(doc).encode()


class _EarlyAnswer:
    """A connection that, when the daemon answers before taking the whole
    body (a 401, 413 or 415 decided from the request head) and closes, stops
    sending and reads that answer instead of failing with a broken pipe."""

    def send(self, data):
        try:
            super().send(data)
        except (BrokenPipeError, ConnectionResetError):
            pass  # getresponse() reads the answer, or finds none (no answer)


class _EarlyAnswerHTTP(_EarlyAnswer, http.client.HTTPConnection):
    pass


class _EarlyAnswerHTTPS(_EarlyAnswer, http.client.HTTPSConnection):
    pass


class _HTTPHandler(urllib.request.HTTPHandler):
    def http_open(self, req):
        return self.do_open(_EarlyAnswerHTTP, req)


class _HTTPSHandler(urllib.request.HTTPSHandler):
    def https_open(self, req):
        return self.do_open(_EarlyAnswerHTTPS, req, context=self._context)


_OPENER = urllib.request.build_opener(_HTTPHandler, _HTTPSHandler)


def _read_within(answer, server, timeout):
    """The answer's body, read in pieces so that a daemon sending it a few
    bytes at a time cannot hold the call past timeout seconds (each read
    waits at most that long on its own)."""
    if timeout is None:
        return answer.read()
    deadline, pieces = time.monotonic() + timeout, []
    while True:
        piece = answer.read1(1 << 16)
        if not piece:
            return b"".join(pieces)
        pieces.append(piece)
        if time.monotonic() > deadline:
            raise PointsegError(0, "no complete answer from %s within %g s" % (server, timeout))


def _request(server, method, path, token=None, body=None, content_type=None, timeout=None):
    """(status, headers, bytes) of one request; raises PointsegError on 4xx/5xx."""
    request = urllib.request.Request(server.rstrip("/") + path, data=body, method=method)
    if content_type:
        request.add_header("Content-Type", content_type)
    if token:
        request.add_header("Authorization", "Bearer " + token)
    try:
        with _OPENER.open(request, timeout=timeout) as answer:
            return answer.status, answer.headers, _read_within(answer, server, timeout)
    except urllib.error.HTTPError as e:
        raw = e.read()
        try:
            detail = json.loads(raw).get("detail", raw.decode(errors="replace"))
        except ValueError:
            detail = raw.decode(errors="replace")
        raise PointsegError(e.code, detail) from None
    except urllib.error.URLError as e:
        raise PointsegError(0, "cannot reach %s: %s" % (server, e.reason)) from None
    except (OSError, http.client.HTTPException) as e:
        raise PointsegError(0, "no answer from %s: %s" % (server, e)) from None


def _decode(raw, output):
    if output == "ply":
        return raw
    if output == "labels":
        return [int(line) for line in raw.split()]
    return json.loads(raw)


def _answer_with(raw, server, member):
    """The JSON object of an answer holding member; PointsegError (status 0)
    when the answer is no such object (a wrong server or proxy)."""
    try:
        doc = json.loads(raw)
    except ValueError:
        doc = None
    if not isinstance(doc, dict) or member not in doc:
        raise PointsegError(0, "%s answered without a readable %s" % (server, member))
    return doc


def _seconds_left(deadline, message):
    """The seconds left before deadline (None: no deadline); when none are,
    raises PointsegError with status 0 and message."""
    if deadline is None:
        return None
    left = deadline - time.monotonic()
    if left <= 0:
        raise PointsegError(0, message)
    return left


def _wait(server, job_id, token, poll_seconds, deadline, timeout):
    """Polls the job until it is final; returns its status document."""
    late = "job %s not finished after %g s" % (job_id, timeout or 0)
    while True:
        _, _, raw = _request(server, "GET", "/jobs/" + job_id, token,
                             timeout=_seconds_left(deadline, late))
        status = _answer_with(raw, server, "status")
        if status["status"] in FINAL_STATES:
            return status
        left = _seconds_left(deadline, late)
        time.sleep(poll_seconds if left is None else min(poll_seconds, left))


def segment(path_or_points, server=DEFAULT_SERVER, token=None, output="json",
            async_=False, poll_seconds=POLL_SECONDS, timeout=None, **params):
    """Segments a file (path) or a list of points on pointsegd.

    params are segmentation parameters (k=10, persistence=0.05, ...), sent in
    the query string.  With async_=True the job is queued (POST /jobs) and
    polled every poll_seconds until done.  timeout (seconds, None = none)
    bounds the whole call, every poll and the result request included: each
    request has the time left as its socket timeout, and a call out of time
    raises PointsegError with status 0.  Returns the document (see the
    module comment).
    """
    return _segment(path_or_points, server, token, output, async_, poll_seconds, timeout,
                    params)


def _segment(path_or_points, server, token, output, async_, poll_seconds, timeout, params):
    """segment() with its parameters in a dict, so that any name can be one."""
    deadline = time.monotonic() + timeout if timeout else None
    body, content_type = _body_of(path_or_points)
    query = dict(params, output=output)
    body = _without_overridden(body, {_spelt(name) for name in query})
    query = urllib.parse.urlencode({k: _param_text(v) for k, v in query.items()})
    if not async_:
        _, _, raw = _request(server, "POST", "/segment?" + query, token, body, content_type,
                             timeout)
        return _decode(raw, output)
    _, _, raw = _request(server, "POST", "/jobs?" + query, token, body, content_type, timeout)
    job_id = str(_answer_with(raw, server, "id")["id"])
    _wait(server, job_id, token, poll_seconds, deadline, timeout)
    late = "job %s: no result after %g s" % (job_id, timeout or 0)
    _, _, raw = _request(server, "GET", "/jobs/%s/result" % job_id, token,
                         timeout=_seconds_left(deadline, late))
    return _decode(raw, output)


def _param_text(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    return str(value)


def _write(doc, output, out):
    if output == "ply":
        raw = doc
    elif output == "labels":
        raw = "".join("%d\n" % label for label in doc).encode()
    else:
        raw = (json.dumps(doc) + "\n").encode()
    if out in (None, "-"):
        sys.stdout.buffer.write(raw)
        sys.stdout.buffer.flush()
    else:
        with open(out, "wb") as f:
            f.write(raw)


class _InOrder(argparse.Action):
    """Keeps --param NAME=VALUE and --output VALUE (as output=VALUE) in
    args.params in the order given, so that a later one can override."""

    def __call__(self, parser, namespace, value, option_string=None):
        item = value if option_string == "--param" else "output=" + value
        namespace.params = namespace.params + [item]


def _last_params(items):
    """{name: value} of "NAME=VALUE" items, of a name given more than once the
    last (_spelt); None on an item
    without '='."""
    params = {}
    for item in items:
        name, sep, value = item.partition("=")
        if not sep:
            print("pointseg_client.py: --param %s: expected NAME=VALUE" % item, file=sys.stderr)
            return None
        params[_spelt(name)] = value
    return params


def _parse_args(argv):
    parser = argparse.ArgumentParser(prog="pointseg_client.py",
                                     description="Segment a point set on pointsegd.")
    commands = parser.add_subparsers(dest="command", required=True)
    seg = commands.add_parser("segment", help="segment FILE on the daemon")
    seg.add_argument("file", help="PLY, OFF, OBJ, XYZ/CSV or JSON point set")
    seg.add_argument("--server", default=DEFAULT_SERVER, help="daemon URL (%(default)s)")
    seg.add_argument("--async", dest="async_", action="store_true",
                     help="queue a job (POST /jobs) and poll it")
    seg.add_argument("--output", dest="params", action=_InOrder, default=[], choices=OUTPUTS,
                     help="json (default), labels or ply; the same as --param output=...")
    seg.add_argument("-o", dest="out", help="write the result here (default stdout)")
    seg.add_argument("--token", default=os.environ.get("POINTSEG_TOKEN"),
                     help="bearer token (default $POINTSEG_TOKEN)")
    seg.add_argument("--param", dest="params", action=_InOrder, default=[],
                     metavar="NAME=VALUE",
                     help="a segmentation parameter, e.g. --param k=10 (repeatable; as "
                          "with pointseg's flags, a later one overrides an earlier one)")
    return parser.parse_args(argv)


def main(argv=None):
    args = _parse_args(sys.argv[1:] if argv is None else argv)
    params = _last_params(args.params)
    if params is None:
        return 2
    output = params.pop("output", "json")
    if output not in OUTPUTS:
        print("pointseg_client.py: output=%s: expected one of %s" % (output, ", ".join(OUTPUTS)),
              file=sys.stderr)
        return 2
    try:
        doc = _segment(args.file, args.server, args.token, output, args.async_, POLL_SECONDS,
                       None, params)
    except PointsegError as e:
        print("pointseg_client.py: %s: %s" % (args.file, e), file=sys.stderr)
        return 2 if 400 <= e.status < 500 else 1
    except OSError as e:
        print("pointseg_client.py: %s" % e, file=sys.stderr)
        return 2
    _write(doc, output, args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
