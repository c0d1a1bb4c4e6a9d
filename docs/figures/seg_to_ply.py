#!/usr/bin/env python3
"""seg_to_ply.py MESH.off FACES.seg OUT.ply: a human segmentation of the
Princeton benchmark (one segment per face) as an ascii PLY coloured like
pointseg's output (segments numbered by decreasing size, same palette), for
`pointseg render`.  Each vertex takes the segment of the first face using it."""
import sys

PALETTE = [(0xE6, 0x19, 0x4B), (0x3C, 0xB4, 0x4B), (0xFF, 0xE1, 0x19), (0x43, 0x63, 0xD8),
           (0xF5, 0x82, 0x31), (0x91, 0x1E, 0xB4), (0x42, 0xD4, 0xF4), (0xF0, 0x32, 0xE6),
           (0xBF, 0xEF, 0x45), (0xFA, 0xBE, 0xD4), (0x46, 0x99, 0x90), (0xDC, 0xBE, 0xFF),
           (0x9A, 0x63, 0x24), (0xFF, 0xFA, 0xC8), (0x80, 0x00, 0x00), (0xAA, 0xFF, 0xC3),
           (0x80, 0x80, 0x00), (0xFF, 0xD8, 0xB1), (0x00, 0x00, 0x75), (0xA9, 0xA9, 0xA9)]


def read_off(path):
    words = open(path).read().split()
    assert words[0] == "OFF"
    nv, nf = int(words[1]), int(words[2])
    at = 4
    verts = [tuple(map(float, words[at + 3 * i: at + 3 * i + 3])) for i in range(nv)]
    at += 3 * nv
    faces = []
    for _ in range(nf):
        k = int(words[at])
        faces.append(tuple(int(w) for w in words[at + 1: at + 1 + k]))
        at += 1 + k
    return verts, faces


def main():
    mesh, seg, out = sys.argv[1:4]
    verts, faces = read_off(mesh)
    face_seg = [int(line) for line in open(seg) if line.strip()]
    sizes = {}
    for s in face_seg:
        sizes[s] = sizes.get(s, 0) + 1
    rank = {s: i for i, s in enumerate(sorted(sizes, key=lambda s: (-sizes[s], s)))}
    vlabel = [None] * len(verts)
    for face, s in zip(faces, face_seg):
        for v in face:
            if vlabel[v] is None:
                vlabel[v] = rank[s]
    with open(out, "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex %d\n" % len(verts))
        f.write("property float x\nproperty float y\nproperty float z\n")
        f.write("property uchar red\nproperty uchar green\nproperty uchar blue\n")
        f.write("element face %d\nproperty list uchar int vertex_indices\nend_header\n" % len(faces))
        for (x, y, z), lab in zip(verts, vlabel):
            r, g, b = PALETTE[(lab or 0) % len(PALETTE)]
            f.write("%g %g %g %d %d %d\n" % (x, y, z, r, g, b))
        for face in faces:
            f.write("%d %s\n" % (len(face), " ".join(map(str, face))))


if __name__ == "__main__":
    main()
