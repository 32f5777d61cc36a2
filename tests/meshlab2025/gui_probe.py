#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""Helpers of the MeshLab 2025.07 / 2022.02 GUI test (standard library only).

  gui_probe.py torus OUT.ply FACES [--seed N]
      a noisy torus (binary PLY) with at least FACES triangles: an n x m grid of quads, each
      split in two, vertices jittered by a tenth of an edge along the tube's normal
  gui_probe.py bar IMG WxH+X+Y
      the number of pixels of Qt's progress-bar chunk (the Fusion style's highlight blue) in
      that region of a screenshot, so a growing bar gives growing numbers
"""
import math
import random
import struct
import subprocess
import sys


def torus(out, faces, seed):
    rng = random.Random(seed)
    m = max(8, int(math.sqrt(faces / 2 / 4)))        # around the tube
    n = max(8, -(-faces // (2 * m)))                  # along the ring, n x m quads
    R, r = 1.0, 0.35
    jitter = 0.1 * 2 * math.pi * r / m
    with open(out, "wb") as f:
        f.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\n"
                 "property float x\nproperty float y\nproperty float z\n"
                 "element face %d\nproperty list uchar int vertex_indices\nend_header\n"
                 % (n * m, 2 * n * m)).encode())
        buf = bytearray()
        for i in range(n):
            u = 2 * math.pi * i / n
            for j in range(m):
                v = 2 * math.pi * j / m
                d = r + rng.uniform(-jitter, jitter)
                buf += struct.pack("<fff", (R + d * math.cos(v)) * math.cos(u),
                                   (R + d * math.cos(v)) * math.sin(u), d * math.sin(v))
        f.write(buf)
        buf = bytearray()
        for i in range(n):
            for j in range(m):
                a, b = i * m + j, i * m + (j + 1) % m
                c, d = ((i + 1) % n) * m + j, ((i + 1) % n) * m + (j + 1) % m
                buf += struct.pack("<Biii", 3, a, c, d)
                buf += struct.pack("<Biii", 3, a, d, b)
        f.write(buf)
    print("%s: %d vertices, %d faces" % (out, n * m, 2 * n * m))


def bar_pixels(img, geom):
    ppm = subprocess.run(["convert", img, "-crop", geom, "+repage", "-depth", "8", "ppm:-"],
                         capture_output=True, check=True).stdout
    # P6 header: magic, width, height, maxval, each followed by whitespace
    fields, pos = [], 0
    while len(fields) < 4:
        while ppm[pos:pos + 1].isspace():
            pos += 1
        start = pos
        while not ppm[pos:pos + 1].isspace():
            pos += 1
        fields.append(ppm[start:pos])
    pos += 1
    w, h = int(fields[1]), int(fields[2])
    data = ppm[pos:pos + 3 * w * h]
    count = 0
    for k in range(0, len(data), 3):
        r, g, b = data[k], data[k + 1], data[k + 2]
        if b >= 150 and b - r >= 70 and b - g >= 20:   # #308cc6 and its shades
            count += 1
    return count


def main(argv):
    if len(argv) >= 4 and argv[1] == "torus":
        seed = int(argv[argv.index("--seed") + 1]) if "--seed" in argv else 1
        torus(argv[2], int(argv[3]), seed)
        return 0
    if len(argv) == 4 and argv[1] == "bar":
        print(bar_pixels(argv[2], argv[3]))
        return 0
    print(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
