#!/bin/sh
# install-deps.sh: makes sure the Debian packages pointseg builds and tests
# with are installed.  Installs the missing ones with apt-get when it can
# (root, or passwordless sudo); otherwise prints the one command to run and
# fails.  Quiet and fast (one dpkg-query) when nothing is missing.
#   scripts/install-deps.sh          build and run dependencies
#   scripts/install-deps.sh --test   also what `make test` needs
set -eu

PACKAGES="gcc make pkg-config libflann-dev liblapacke-dev libopenblas-dev
libmicrohttpd-dev libcjson-dev libcurl4-openssl-dev zlib1g-dev libhiredis-dev
curl python3"
TEST_PACKAGES="clang redis-server"

[ "${1:-}" = "--test" ] && PACKAGES="$PACKAGES $TEST_PACKAGES"

missing=""
for p in $PACKAGES; do
    status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
    case "$status" in
        *"ok installed"*) ;;
        *) missing="$missing $p" ;;
    esac
done
[ -z "$missing" ] && exit 0

echo "pointseg: installing missing packages:$missing"
if [ "$(id -u)" = 0 ]; then
    SUDO=""
elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
    SUDO="sudo -n"
else
    echo "pointseg: cannot install as $(id -un); run this, then make again:" >&2
    echo "  sudo apt-get update && sudo apt-get install -y$missing" >&2
    exit 1
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
# shellcheck disable=SC2086
$SUDO apt-get install -y -qq --no-install-recommends $missing
