#!/bin/sh
# token.sh: synchronous segmentation on a daemon started with --token
# (POINTSEG_TOKEN): the token goes in an Authorization: Bearer header.
#   POINTSEG_TOKEN=secret clients/curl/token.sh [URL] [FILE]
# URL defaults to http://127.0.0.1:8080, FILE to sample.xyz beside this
# script.  Parameters go in the query string: PARAMS='output=labels'.
set -eu
url=${1:-http://127.0.0.1:8080}
file=${2:-$(dirname "$0")/sample.xyz}
: "${POINTSEG_TOKEN:?set POINTSEG_TOKEN to the token of the daemon}"
curl -sS --fail-with-body -X POST --data-binary @"$file" \
     -H 'Content-Type: application/octet-stream' \
     -H "Authorization: Bearer $POINTSEG_TOKEN" \
     "$url/segment?${PARAMS:-}"
