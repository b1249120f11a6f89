#!/usr/bin/env python3
"""Writes a cube-map sky (px nx py ny pz nz .png, OpenGL's faces) made from a formula of the
direction: a gradient from a warm horizon to a blue zenith, a brown ground, a sun, and a red glow
toward +X (so a mirrored lookup shows).

Usage: scripts/make-sky.py OUT_DIR [--size N] [--three]
  --three  the faces three.js needs to show the same sky: it looks a cube map up at (-x, y, z)
           (../shared/tools/threejs-ref/README.md), so each texel holds the sky of that direction.
"""
import argparse
import math
import os
import struct
import zlib

# Texel direction of face f at (sc, tc) in [-1, 1] (OpenGL 4.5, table 8.19, inverted).
FACES = {
    "px": lambda s, t: (1.0, -t, -s),
    "nx": lambda s, t: (-1.0, -t, s),
    "py": lambda s, t: (s, 1.0, t),
    "ny": lambda s, t: (s, -1.0, -t),
    "pz": lambda s, t: (s, -t, 1.0),
    "nz": lambda s, t: (-s, -t, -1.0),
}


def sky(x, y, z):
    sun = (0.5, 0.6, -0.6)
    n = math.sqrt(sum(c * c for c in sun))
    sun = tuple(c / n for c in sun)
    if y >= 0.0:
        t = math.sqrt(y)
        base = [0.85 + (0.20 - 0.85) * t, 0.75 + (0.40 - 0.75) * t, 0.60 + (0.85 - 0.60) * t]
    else:
        t = min(1.0, -y * 3.0)
        base = [0.40 + (0.30 - 0.40) * t, 0.34 + (0.25 - 0.34) * t, 0.28 + (0.20 - 0.28) * t]
    glow = max(0.0, x * sun[0] + y * sun[1] + z * sun[2]) ** 64
    red = max(0.0, x) ** 4 * 0.3
    return [min(1.0, base[0] + glow + red), min(1.0, base[1] + 0.95 * glow), min(1.0, base[2] + 0.8 * glow)]


def write_png(path, size, rows):
    raw = b"".join(b"\x00" + bytes(r) for r in rows)
    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", size, size, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("--size", type=int, default=64)
    ap.add_argument("--three", action="store_true")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    for name, face in FACES.items():
        rows = []
        for j in range(a.size):
            row = []
            for i in range(a.size):
                d = face(2.0 * (i + 0.5) / a.size - 1.0, 2.0 * (j + 0.5) / a.size - 1.0)
                n = math.sqrt(sum(c * c for c in d))
                x, y, z = (c / n for c in d)
                if a.three:
                    x = -x
                row += [int(round(c * 255.0)) for c in sky(x, y, z)]
            rows.append(row)
        write_png(os.path.join(a.out, name + ".png"), a.size, rows)


if __name__ == "__main__":
    main()
