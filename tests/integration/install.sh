#!/bin/sh
# install.sh: `make install` and `make uninstall` into a scratch DESTDIR.
#   tests/integration/install.sh BUILD     installs BUILD's programs
# Checks the installed programs run, the man pages format without warnings,
# the systemd unit points at the installed daemon, and uninstall removes
# every file.  Prints "PASS install:NAME" / "FAIL install:NAME: why".
set -u
BUILD=${1:-build}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
dest=$tmp/root
prefix=/opt/pointseg
failures=0

pass() { echo "PASS install:$1"; }
fail() { echo "FAIL install:$1: $2"; failures=$((failures + 1)); }

if ! make -s --no-print-directory -C "$ROOT" BUILD="$BUILD" DESTDIR="$dest" PREFIX="$prefix" \
        install >"$tmp/make.log" 2>&1; then
    fail install "make install failed: $(tail -c 400 "$tmp/make.log")"
    exit 1
fi
pass install

for prog in pointseg pointsegd; do
    if "$dest$prefix/bin/$prog" --version 2>&1 | grep -q "^$prog "; then pass "$prog"
    else fail "$prog" "$dest$prefix/bin/$prog --version does not name itself"; fi
done

for page in man1/pointseg.1 man8/pointsegd.8; do
    file=$dest$prefix/share/man/$page
    if [ ! -f "$file" ]; then
        fail "$page" "not installed"
    elif ! command -v groff >/dev/null 2>&1; then
        echo "SKIP install:$page: groff not found, format not checked"
    elif groff -man -ww -z "$file" 2>"$tmp/groff.err" && [ ! -s "$tmp/groff.err" ]; then
        pass "$page"
    else
        fail "$page" "groff: $(head -c 300 "$tmp/groff.err")"
    fi
done

unit=$dest$prefix/lib/systemd/system/pointsegd.service
if grep -q "^ExecStart=$prefix/bin/pointsegd --static-dir $prefix/share/pointseg/web\$" "$unit" 2>/dev/null &&
    ! grep -q '@' "$unit"; then pass systemd-unit
else fail systemd-unit "ExecStart is not the installed daemon: $(grep ExecStart "$unit" 2>&1)"; fi

make -s --no-print-directory -C "$ROOT" BUILD="$BUILD" DESTDIR="$dest" PREFIX="$prefix" \
    uninstall >"$tmp/make.log" 2>&1
left=$(find "$dest" -type f | head -5)
[ -z "$left" ] && pass uninstall || fail uninstall "left behind: $left"

[ "$failures" -eq 0 ]
