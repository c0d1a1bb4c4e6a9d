#!/usr/bin/env python3
"""grid_png.py COLUMNS OUT.png IN.png...: puts same-sized PNGs written by
`pointseg render` (8-bit RGB, filter 0 rows) into a grid, row by row."""
import struct
import sys
import zlib


def read_png(path):
    data = open(path, "rb").read()
    at, width, height, idat = 8, 0, 0, b""
    while at < len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8: at + 8 + length]
        if kind == b"IHDR":
            width, height = struct.unpack(">II", body[:8])
            assert body[8] == 8 and body[9] == 2, "8-bit RGB only"
        elif kind == b"IDAT":
            idat += body
        at += 12 + length
    raw = zlib.decompress(idat)
    stride = 3 * width + 1
    rows = []
    for y in range(height):
        row = raw[y * stride: (y + 1) * stride]
        assert row[0] == 0, "filter 0 rows only"
        rows.append(row[1:])
    return width, height, rows


def chunk(kind, body):
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))


def main():
    columns, out, paths = int(sys.argv[1]), sys.argv[2], sys.argv[3:]
    images = [read_png(p) for p in paths]
    width, height = images[0][0], images[0][1]
    blank = b"\xff" * (3 * width)
    n_rows = (len(images) + columns - 1) // columns
    raw = b""
    for r in range(n_rows):
        for y in range(height):
            line = b""
            for c in range(columns):
                i = r * columns + c
                line += images[i][2][y] if i < len(images) else blank
            raw += b"\x00" + line
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width * columns,
                                                          height * n_rows, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    open(out, "wb").write(png)


if __name__ == "__main__":
    main()
