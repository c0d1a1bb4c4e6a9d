#!/bin/sh
# render.sh: shell tests of `pointseg render` (clients/cli/render.c).
#   tests/integration/render.sh BUILD     uses BUILD/pointseg
# Draws a red triangle (faces) and two coloured points (splats) from small
# ascii PLY files, decodes the PNGs with Python's zlib and checks size,
# colours, shading and background; then usage errors.  Prints
# "PASS render:NAME" / "FAIL render:NAME: why"; exits 1 on any failure.
SUITE=render
. "$(dirname "$0")/lib.sh"

# pixel PNG X Y: prints "r g b" of pixel (X, Y) (Y down), or an error line.
pixel() {
    python3 - "$@" <<'PY'
import struct, sys, zlib
data = open(sys.argv[1], "rb").read()
x, y = int(sys.argv[2]), int(sys.argv[3])
assert data[:8] == b"\x89PNG\r\n\x1a\n", "no PNG signature"
pos, idat, width = 8, b"", 0
while pos < len(data):
    n, kind = struct.unpack(">I4s", data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + n]
    crc = struct.unpack(">I", data[pos + 8 + n:pos + 12 + n])[0]
    assert zlib.crc32(kind + body) == crc, "bad CRC"
    if kind == b"IHDR":
        width, height, depth, colour = struct.unpack(">IIBB", body[:10])
        assert (depth, colour) == (8, 2), "not 8-bit RGB"
    if kind == b"IDAT":
        idat += body
    pos += 12 + n
raw = zlib.decompress(idat)
row = raw[y * (3 * width + 1):(y + 1) * (3 * width + 1)]
assert row[0] == 0, "filter type is not 0"
print(*row[1 + 3 * x:4 + 3 * x])
PY
}

# png_size PNG: "W H" from IHDR.
png_size() {
    python3 -c 'import struct,sys; print(*struct.unpack(">II", open(sys.argv[1],"rb").read()[16:24]))' "$1"
}

if [ ! -x "$PS" ]; then
    fail setup "$PS is not built"
    exit 1
fi

cat >"$tmp/tri.ply" <<'PLY'
ply
format ascii 1.0
element vertex 3
property float x
property float y
property float z
property uchar red
property uchar green
property uchar blue
element face 1
property list uchar int vertex_indices
end_header
0 0 0 200 0 0
1 0 0 200 0 0
0 1 0 200 0 0
3 0 1 2
PLY

"$PS" render "$tmp/tri.ply" -o "$tmp/tri.png" --width 64 --height 48 2>"$tmp/err"
status=$?
if [ "$status" -ne 0 ]; then
    fail triangle "exit status $status: $(cat "$tmp/err")"
else
    size=$(png_size "$tmp/tri.png")
    [ "$size" = "64 48" ] && pass size || fail size "IHDR says $size"
    # Facing the eye: ambient + the light's share toward the eye; pure red.
    inside=$(pixel "$tmp/tri.png" 20 30) corner=$(pixel "$tmp/tri.png" 60 2)
    set -- $inside
    if [ "$#" -eq 3 ] && [ "$1" -gt 120 ] && [ "$1" -le 200 ] && [ "$2" -eq 0 ] && [ "$3" -eq 0 ]; then
        pass triangle
    else
        fail triangle "pixel inside the triangle is '$inside'"
    fi
    [ "$corner" = "255 255 255" ] && pass background || fail background "corner pixel '$corner'"
fi

# Seen edge-on from +x the triangle is a line: only a few columns covered.
"$PS" render "$tmp/tri.ply" -o "$tmp/edge.png" --width 32 --height 32 --view 1,0,0 2>/dev/null
mid=$(pixel "$tmp/edge.png" 2 16)
[ "$mid" = "255 255 255" ] && pass view || fail view "pixel left of the edge-on triangle is '$mid'"

cat >"$tmp/pts.ply" <<'PLY'
ply
format ascii 1.0
element vertex 2
property float x
property float y
property float z
property float red
property float green
property float blue
end_header
0 0 0 0 0 1
4 0 0 0 1 0
PLY
"$PS" render "$tmp/pts.ply" -o "$tmp/pts.png" --width 100 --height 20 2>"$tmp/err"
status=$?
if [ "$status" -eq 0 ]; then
    left=$(pixel "$tmp/pts.png" 6 10) right=$(pixel "$tmp/pts.png" 93 10)
    case "$left/$right" in
        "0 0 "*"/0 "*" 0") pass points ;;
        *) fail points "left '$left' (want blue), right '$right' (want green)" ;;
    esac
else
    fail points "exit status $status: $(cat "$tmp/err")"
fi

expect_usage() { # NAME ARGS...
    name=$1
    shift
    "$PS" render "$@" >/dev/null 2>"$tmp/err"
    rc=$?
    if [ "$rc" -eq 2 ] && grep -q '^pointseg: ' "$tmp/err"; then pass "$name"
    else fail "$name" "exit status $rc, stderr: $(head -c 200 "$tmp/err")"; fi
}
expect_usage no-output "$tmp/tri.ply"
expect_usage bad-width "$tmp/tri.ply" -o "$tmp/x.png" --width 0
expect_usage bad-view "$tmp/tri.ply" -o "$tmp/x.png" --view 1,2
expect_usage missing-file "$tmp/none.ply" -o "$tmp/x.png"
"$PS" render --help | grep -q '^usage: pointseg render' && pass help || fail help "no usage line"

[ "$failures" -eq 0 ]
