#!/bin/sh
# ply.sh: segmentation as a PLY coloured by segment (Accept:
# application/ply), written to OUT (default parts.ply); open it in MeshLab,
# or draw it with `pointseg render OUT -o parts.png`.  An error answer's
# problem goes to stderr and OUT is left as it was.
#   clients/curl/ply.sh [URL] [FILE] [OUT]
# URL defaults to http://127.0.0.1:8080, FILE to sample.xyz beside this
# script.
set -eu
url=${1:-http://127.0.0.1:8080}
file=${2:-$(dirname "$0")/sample.xyz}
out=${3:-parts.ply}
part=$out.$$.part
if curl -sS --fail-with-body -X POST --data-binary @"$file" \
        -H 'Content-Type: application/octet-stream' -H 'Accept: application/ply' \
        -o "$part" "$url/segment?${PARAMS:-}"; then
    mv "$part" "$out"
else
    rc=$?
    if [ -s "$part" ]; then cat "$part" >&2; echo >&2; fi
    rm -f "$part"
    exit "$rc"
fi
echo "wrote $out" >&2
