#!/usr/bin/env python3
# Writes a glTF 2.0 scene with N punctual lights (KHR_lights_punctual): the lights benchmark.
"""Usage: scripts/make-lights-scene.py OUT.gltf [--lights N] [--kind white|mixed] [--transparent]
                                    [--texel-alpha opaque|mask|blend]

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
--texel-alpha: the floor gets uvs (8 repeats across) and an embedded 64 x 64 PNG of green discs
  whose alpha is 255 inside and 0 outside (mask; alphaMode MASK, cutoff 0.5), falls from 255 to
  0 outward (blend; alphaMode BLEND), or is 255 everywhere (opaque: the same texture and
  alphaMode MASK, which the renderer draws as opaque: the baseline of the texel alpha cost).
Python 3 standard library only; the same arguments give the same bytes.
"""
import argparse
import base64
import json
import math
import struct
import sys
import zlib


def png_rgba(width, height, pixel):
    """A PNG (8-bit RGBA, no interlace) of pixel(x, y) -> (r, g, b, a), top row first."""
    raw = bytearray()
    for y in range(height):
        raw.append(0)  # filter: none
        for x in range(width):
            raw.extend(pixel(x, y))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(bytes(raw), 9)) + chunk(b"IEND", b""))


def disc_texel(mode):
    def pixel(x, y):
        d = math.hypot((x % 32) - 15.5, (y % 32) - 15.5) / 14.0  # four discs of radius 14 texels
        if mode == "opaque":
            a = 255
        elif mode == "mask":
            a = 255 if d <= 1.0 else 0
        else:
            a = max(0, min(255, int(round(255 * (1.0 - d)))))
        return (40, 160 + (x * 3) % 64, 60, a)
    return pixel


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
    ap.add_argument("--texel-alpha", choices=["opaque", "mask", "blend"])
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

    def primitive(pos, nrm, idx, material, uvs=None):
        attributes = {"POSITION": add(pos, "f", 5126, "VEC3", 34962, True), "NORMAL": add(nrm, "f", 5126, "VEC3", 34962)}
        if uvs:
            attributes["TEXCOORD_0"] = add(uvs, "f", 5126, "VEC2", 34962)
        return {"attributes": attributes, "indices": add(idx, "I", 5125, "SCALAR", 34963), "material": material}

    fpos, fnrm, fidx = floor(40.0, 32)
    fuvs = [(p[0] / 5.0, p[2] / 5.0) for p in fpos] if a.texel_alpha else None
    meshes = [{"primitives": [primitive(fpos, fnrm, fidx, 0, fuvs)]}]
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
    floor_material = {"name": "floor", "pbrMetallicRoughness": grey}
    textures = {}
    if a.texel_alpha:
        png = png_rgba(64, 64, disc_texel(a.texel_alpha))
        floor_material = {"name": "floor", "alphaMode": "BLEND" if a.texel_alpha == "blend" else "MASK", "doubleSided": True,
                          "pbrMetallicRoughness": dict(grey, baseColorFactor=[1.0, 1.0, 1.0, 1.0], baseColorTexture={"index": 0})}
        textures = {"images": [{"uri": "data:image/png;base64," + base64.b64encode(png).decode()}],
                    "textures": [{"source": 0, "sampler": 0}],
                    "samplers": [{"magFilter": 9729, "minFilter": 9729, "wrapS": 10497, "wrapT": 10497}]}
    doc = {
        "asset": {"version": "2.0", "generator": "SoftRaster scripts/make-lights-scene.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": lights}},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": [floor_material,
                      {"name": "sphere", "pbrMetallicRoughness": dict(grey, baseColorFactor=[0.9, 0.9, 0.9, 1.0])},
                      {"name": "glass", "alphaMode": "BLEND",
                       "pbrMetallicRoughness": dict(grey, baseColorFactor=[0.6, 0.8, 1.0, 0.5])}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.5, "zfar": 200.0}}],
        "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}],
        "bufferViews": views,
        "accessors": accessors,
        **textures,
    }
    with open(a.out, "w") as f:
        json.dump(doc, f, separators=(",", ":"))


if __name__ == "__main__":
    main()
