#!/bin/sh
# healthcheck.sh: docker/Dockerfile's HEALTHCHECK, installed in the image as
# pointseg-healthcheck: GET /healthz where pointsegd listens; exit status 0
# (healthy) or 1 (unhealthy), as Docker reads it.
#   pointseg-healthcheck [PID]
# The address and port are the ones the daemon was given: --bind and --port
# on its command line (/proc/PID/cmdline; PID 1, the container's entry
# point, by default) win over POINTSEG_BIND and POINTSEG_PORT, as in
# pointsegd, and pointsegd's defaults (127.0.0.1, 8080) come last.  A
# daemon listening on every address (0.0.0.0) is asked on loopback.
set -u
bind=${POINTSEG_BIND:-127.0.0.1}
port=${POINTSEG_PORT:-8080}

# --bind ADDR or --bind=ADDR, the same for --port; the last given wins.
prev=
while IFS= read -r arg; do
    case $prev in
        --bind) bind=$arg ;;
        --port) port=$arg ;;
    esac
    case $arg in
        --bind=*) bind=${arg#--bind=} ;;
        --port=*) port=${arg#--port=} ;;
    esac
    prev=$arg
done <<EOF_ARGS
$(tr '\0' '\n' 2>/dev/null <"/proc/${1:-1}/cmdline")
EOF_ARGS

[ "$bind" = 0.0.0.0 ] && bind=127.0.0.1
curl -fsS "http://$bind:$port/healthz" || exit 1
