#!/usr/bin/env python3
# Writes a flat N x N quad grid as OBJ + MTL + two tiny PPM textures: the material-switch stress model.
"""Usage: scripts/make-grid.py OUTDIR [--quads N | --triangles T] [--materials alternate|one] [--name NAME]

OUTDIR/NAME.obj   (N+1)^2 vertices in the z = 0 plane (x, y = column, row), one 'vt' per vertex
                  (u, v = column, row: every quad maps the whole texture once, wrap mode repeat),
                  N*N quads as 'f' lines (tinyobjloader splits each into 2 triangles).
OUTDIR/NAME.mtl   two materials, 'a' and 'b', each with its own map_Kd.
OUTDIR/grid_a.ppm, grid_b.ppm   4x4 textures (binary P6), warm and cool checkerboards.

--materials alternate (default): quad (col, row) uses 'a' when col + row is even, else 'b' (a
checkerboard: a 'usemtl' before every quad, the worst case for per-switch work).
--materials one: every quad uses 'a' (one 'usemtl'); the same geometry, the baseline.
--triangles T picks the smallest N with 2*N*N >= T (default: --quads 600 = 720,000 triangles).
Python 3 standard library only; the same arguments give the same bytes.
"""
import argparse
import math
import os
import sys


def texture(path, warm):
    # 4x4 checkerboard of two colours, written as a binary PPM (stb_image's PNM decoder reads it).
    c0, c1 = ((230, 120, 40), (250, 220, 90)) if warm else ((40, 90, 200), (120, 200, 240))
    pixels = bytearray()
    for y in range(4):
        for x in range(4):
            pixels += bytes(c0 if (x + y) % 2 == 0 else c1)
    with open(path, "wb") as f:
        f.write(b"P6\n4 4\n255\n" + bytes(pixels))


def main(argv):
    ap = argparse.ArgumentParser(description="Quad grid OBJ/MTL/PPM generator (material-switch stress model).")
    ap.add_argument("outdir")
    size = ap.add_mutually_exclusive_group()
    size.add_argument("--quads", type=int, help="quads per side (default 600)")
    size.add_argument("--triangles", type=int, help="at least this many triangles (2 per quad)")
    ap.add_argument("--materials", choices=("alternate", "one"), default="alternate")
    ap.add_argument("--name", help="base name of the .obj/.mtl (default grid_<materials>_<N>)")
    a = ap.parse_args(argv)
    if a.triangles is not None:
        if a.triangles < 2:
            ap.error("--triangles must be >= 2")
        n = math.isqrt((a.triangles + 1) // 2)
        while 2 * n * n < a.triangles:
            n += 1
    else:
        n = 600 if a.quads is None else a.quads
    if n < 1:
        ap.error("--quads must be >= 1")
    name = a.name or "grid_%s_%d" % (a.materials, n)
    os.makedirs(a.outdir, exist_ok=True)

    texture(os.path.join(a.outdir, "grid_a.ppm"), warm=True)
    texture(os.path.join(a.outdir, "grid_b.ppm"), warm=False)
    with open(os.path.join(a.outdir, name + ".mtl"), "w", newline="\n") as f:
        f.write("newmtl a\nKd 1 1 1\nmap_Kd grid_a.ppm\nnewmtl b\nKd 1 1 1\nmap_Kd grid_b.ppm\n")

    side = n + 1
    with open(os.path.join(a.outdir, name + ".obj"), "w", newline="\n") as f:
        w = f.write
        w("# %d x %d quad grid, %d triangles, materials: %s (scripts/make-grid.py)\n" % (n, n, 2 * n * n, a.materials))
        w("mtllib %s.mtl\n" % name)
        # Integer coordinates keep the file short (4M triangles stay below the loader's 256 MiB).
        for row in range(side):
            w("".join("v %d %d 0\n" % (col, row) for col in range(side)))
        for row in range(side):
            w("".join("vt %d %d\n" % (col, row) for col in range(side)))
        current = None
        for row in range(n):
            lines = []
            for col in range(n):
                mat = "a" if a.materials == "one" or (col + row) % 2 == 0 else "b"
                if mat != current:
                    lines.append("usemtl %s\n" % mat)
                    current = mat
                # Counter-clockwise seen from +z; vertex k of row r, column c is r * side + c + 1.
                v0 = row * side + col + 1
                v1, v2, v3 = v0 + 1, v0 + 1 + side, v0 + side
                lines.append("f %d/%d %d/%d %d/%d %d/%d\n" % (v0, v0, v1, v1, v2, v2, v3, v3))
            w("".join(lines))
    print(os.path.join(a.outdir, name + ".obj"))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
