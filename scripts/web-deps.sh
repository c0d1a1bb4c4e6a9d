#!/bin/sh
# web-deps.sh: the Debian packages of the web viewer (clients/web) and its
# browser test.  Installs what is missing with apt-get, as root only.
#   scripts/web-deps.sh            npm, for `make web`; otherwise prints the
#                                  command to run and exits 1
#   scripts/web-deps.sh --browser  also chromium, for `make test-browser`;
#                                  exits 3 when it is missing and this is
#                                  not root (the test then skips)
set -eu

missing=""
command -v npm >/dev/null 2>&1 || missing="nodejs npm"
[ "${1:-}" = "--browser" ] && [ ! -x /usr/bin/chromium ] && missing="$missing chromium"
[ -z "$missing" ] && exit 0

if [ "$(id -u)" != 0 ]; then
    echo "pointseg: missing$missing; as root: apt-get update && apt-get install -y$missing" >&2
    case "$missing" in *npm*) exit 1 ;; esac
    exit 3
fi
echo "pointseg: installing$missing"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
# shellcheck disable=SC2086
apt-get install -y -qq --no-install-recommends $missing >/dev/null
