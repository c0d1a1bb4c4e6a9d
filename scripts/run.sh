#!/bin/sh
# run.sh: what `make run` starts: pointsegd in the foreground on 127.0.0.1:8080
# (override with POINTSEG_PORT / POINTSEG_BIND or flags in RUN_ARGS).
set -eu
BUILD=${1:-build}
port=${POINTSEG_PORT:-8080}
echo "pointsegd on http://127.0.0.1:$port  (Ctrl-C stops it)"
echo "try:  curl -s -X POST --data-binary @clients/curl/sample.xyz -H 'Content-Type: application/octet-stream' http://127.0.0.1:$port/segment | head -c 400"
# shellcheck disable=SC2086
exec "$BUILD/pointsegd" ${RUN_ARGS:-}
