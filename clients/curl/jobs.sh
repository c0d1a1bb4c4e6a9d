#!/bin/sh
# jobs.sh: asynchronous segmentation: POST /jobs, poll GET /jobs/{id} until
# the job is done (progress on stderr), then GET /jobs/{id}/result on stdout.
# An error answer's problem goes to stderr.
#   clients/curl/jobs.sh [URL] [FILE]
# URL defaults to http://127.0.0.1:8080, FILE to sample.xyz beside this
# script.  Parameters go in the query string: PARAMS='output=labels'.
set -eu
url=${1:-http://127.0.0.1:8080}
file=${2:-$(dirname "$0")/sample.xyz}
field() { sed -n "s/.*\"$1\":\"\\([^\"]*\\)\".*/\\1/p"; }
# call ARGS...: curl's answer on stdout; an error answer's problem goes to
# stderr and curl's exit status is returned.
call() {
    answer=$(curl -sS --fail-with-body "$@") || { rc=$?; printf '%s\n' "$answer" >&2; return "$rc"; }
    printf '%s\n' "$answer"
}

job=$(call -X POST --data-binary @"$file" \
           -H 'Content-Type: application/octet-stream' "$url/jobs?${PARAMS:-}")
id=$(printf '%s' "$job" | field id)
echo "job $id" >&2
while :; do
    status=$(call "$url/jobs/$id")
    state=$(printf '%s' "$status" | field status)
    echo "  $state $(printf '%s' "$status" | field phase)" >&2
    case "$state" in
        done | failed | cancelled) break ;;
    esac
    sleep 0.2
done
curl -sS --fail-with-body "$url/jobs/$id/result"
