#!/bin/sh
# segment.sh: synchronous segmentation: POST /segment, the answer on stdout.
#   clients/curl/segment.sh [URL] [FILE]
# URL defaults to http://127.0.0.1:8080, FILE to sample.xyz beside this
# script (any format pointsegd reads).  Parameters go in the query string:
# PARAMS='output=labels&k=10' clients/curl/segment.sh
set -eu
url=${1:-http://127.0.0.1:8080}
file=${2:-$(dirname "$0")/sample.xyz}
curl -sS --fail-with-body -X POST --data-binary @"$file" \
     -H 'Content-Type: application/octet-stream' \
     "$url/segment?${PARAMS:-}"
