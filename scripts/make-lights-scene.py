#!/usr/bin/env python3
# Writes a glTF 2.0 scene with N punctual lights (KHR_lights_punctual): the lights benchmark (issue 16).
"""Usage: scripts/make-lights-scene.py OUT.gltf [--lights N] [--kind white|mixed] [--transparent]

The scene: a 40 x 40 floor of 32 x 32 quads at y = 0 and a 5 x 5 grid of UV spheres (radius 1.5,
24 x 16 segments) standing on it, one material each for the floor and the spheres (grey, ks 0.04
from metallic 0 - a Blinn-Phong specular term), and a perspective camera looking down at it
(`--camera 0`). Everything is in one embedded buffer (a data: URI).

--lights N (default 1): N lights.
--kind white (default): N white directional lights of intensity 1/N (the one-number fast path
  when N = 1 ... every white directional light keeps it).
--kind mixed: coloured lights cycling point, spot, directional (point and spot lights above the
  spheres, range 30): the RGB path.
--transparent: every other sphere is BLEND with alpha 0.5 (drawn sorted, after the opaque ones).
Python 3 standard library only; the same arguments give the same bytes.
"""
import argparse
import base64
import json
import math
import struct
import sys


def sphere(cx, cy, cz, r, seg=24, rings=16):
    pos, nrm, idx = [], [], []
    for i in range(rings + 1):
        th = math.pi * i / rings
        for j in range(seg + 1):
            ph = 2 * math.pi * j / seg
            n = (math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph))
            nrm.append(n)
            pos.append((cx + r * n[0], cy + r * n[1], cz + r * n[2]))
    for i in range(rings):
        for j in range(seg):
            a = i * (seg + 1) + j
            b = a + seg + 1
            idx += [a, a + 1, b, a + 1, b + 1, b]  # counter-clockwise seen from outside
    return pos, nrm, idx


def floor(size, n):
    pos, nrm, idx = [], [], []
    for i in range(n + 1):
        for j in range(n + 1):
            pos.append((-size / 2 + size * j / n, 0.0, -size / 2 + size * i / n))
            nrm.append((0.0, 1.0, 0.0))
    for i in range(n):
        for j in range(n):
            a = i * (n + 1) + j
            b = a + n + 1
            idx += [a, b, a + 1, a + 1, b, b + 1]  # counter-clockwise seen from above
    return pos, nrm, idx


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("--lights", type=int, default=1)
    ap.add_argument("--kind", choices=["white", "mixed"], default="white")
    ap.add_argument("--transparent", action="store_true")
    a = ap.parse_args()
    if not 1 <= a.lights <= 64:
        sys.exit("make-lights-scene: --lights must be in 1..64")

    blob = bytearray()
    views, accessors = [], []

    def add(values, fmt, comp, typ, target, minmax=False):
        while len(blob) % 4:
            blob.append(0)
        start = len(blob)
        flat = [x for v in values for x in (v if isinstance(v, tuple) else (v,))]
        blob.extend(struct.pack("<%d%s" % (len(flat), fmt), *flat))
        views.append({"buffer": 0, "byteOffset": start, "byteLength": len(blob) - start, "target": target})
        acc = {"bufferView": len(views) - 1, "componentType": comp, "count": len(values), "type": typ}
        if minmax:
            acc["min"] = [min(v[k] for v in values) for k in range(3)]
            acc["max"] = [max(v[k] for v in values) for k in range(3)]
        accessors.append(acc)
        return len(accessors) - 1

    def primitive(pos, nrm, idx, material):
        return {"attributes": {"POSITION": add(pos, "f", 5126, "VEC3", 34962, True),
                               "NORMAL": add(nrm, "f", 5126, "VEC3", 34962)},
                "indices": add(idx, "I", 5125, "SCALAR", 34963), "material": material}

    meshes = [{"primitives": [primitive(*floor(40.0, 32), 0)]}]
    nodes = [{"mesh": 0}]
    for k in range(25):
        gx, gz = k % 5, k // 5
        meshes.append({"primitives": [primitive(*sphere(-12 + 6 * gx, 1.5, -12 + 6 * gz, 1.5), 2 if a.transparent and k % 2 else 1)]})
        nodes.append({"mesh": len(meshes) - 1})

    lights = []
    palette = [(1.0, 0.85, 0.7), (0.6, 0.8, 1.0), (1.0, 0.5, 0.5), (0.5, 1.0, 0.6)]
    for k in range(a.lights):
        ang = 2 * math.pi * k / a.lights
        if a.kind == "white":
            lights.append({"type": "directional", "intensity": 1.0 / a.lights})
            # turn -z toward the light direction (-1 + k, -2, -1) rotated about y by ang
            d = (math.cos(ang) * -1 - math.sin(ang) * -1, -2.0, math.sin(ang) * -1 + math.cos(ang) * -1)
            pos = None
        else:
            kind = ["point", "spot", "directional"][k % 3]
            light = {"type": kind, "color": list(palette[k % 4])}
            if kind == "directional":
                light["intensity"] = 0.5
                d = (math.cos(ang), -2.0, math.sin(ang))
                pos = None
            else:
                light["intensity"] = 120.0
                light["range"] = 30.0
                pos = (9 * math.cos(ang), 8.0, 9 * math.sin(ang))
                d = (-pos[0] * 0.5, -pos[1], -pos[2] * 0.5)
                if kind == "spot":
                    light["spot"] = {"innerConeAngle": 0.3, "outerConeAngle": 0.7}
            lights.append(light)
        # A rotation taking -z to d: axis = (-z) x d, angle between them.
        n = math.sqrt(sum(c * c for c in d))
        d = tuple(c / n for c in d)
        axis = (d[1], -d[0], 0.0)  # (0, 0, -1) x d
        s = math.sqrt(axis[0] ** 2 + axis[1] ** 2)
        cosang = -d[2]
        node = {"extensions": {"KHR_lights_punctual": {"light": k}}}
        if s > 1e-9:
            half = math.atan2(s, cosang) / 2
            node["rotation"] = [axis[0] / s * math.sin(half), axis[1] / s * math.sin(half), 0.0, math.cos(half)]
        if pos:
            node["translation"] = list(pos)
        nodes.append(node)

    # Camera at (0, 22, 30) looking at the origin: a rotation about x by -atan(22 / 30).
    tilt = -math.atan2(22.0, 30.0)
    nodes.append({"camera": 0, "translation": [0.0, 22.0, 30.0], "rotation": [math.sin(tilt / 2), 0.0, 0.0, math.cos(tilt / 2)]})

    grey = {"baseColorFactor": [0.8, 0.8, 0.8, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.5}
    doc = {
        "asset": {"version": "2.0", "generator": "SoftRaster scripts/make-lights-scene.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": lights}},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": [{"name": "floor", "pbrMetallicRoughness": grey},
                      {"name": "sphere", "pbrMetallicRoughness": dict(grey, baseColorFactor=[0.9, 0.9, 0.9, 1.0])},
                      {"name": "glass", "alphaMode": "BLEND",
                       "pbrMetallicRoughness": dict(grey, baseColorFactor=[0.6, 0.8, 1.0, 0.5])}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.5, "zfar": 200.0}}],
        "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}],
        "bufferViews": views,
        "accessors": accessors,
    }
    with open(a.out, "w") as f:
        json.dump(doc, f, separators=(",", ":"))


if __name__ == "__main__":
    main()
