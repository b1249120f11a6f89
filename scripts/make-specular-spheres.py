#!/usr/bin/env python3
# Writes a glTF of four dielectric spheres of one base colour: plain, KHR_materials_ior 2.5,
# KHR_materials_specular factor 0.2, and ior 1.8 with a tinted specularColorFactor (a sweep for
# scripts/compare-threejs.sh). Usage: scripts/make-specular-spheres.py OUT.gltf [--plain: without the extensions]
import base64
import json
import math
import struct
import sys
# A UV sphere (radius 1), four spheres with dielectric variants of one base colour.
st, sl = 48, 24
pos, nrm, idx = [], [], []
for i in range(sl + 1):
    th = math.pi * i / sl
    for j in range(st + 1):
        ph = 2 * math.pi * j / st
        x, y, z = math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph)
        pos += [x, y, z]; nrm += [x, y, z]
for i in range(sl):
    for j in range(st):
        a = i * (st + 1) + j; b = a + st + 1
        idx += [a, a + 1, b, a + 1, b + 1, b]
blob = struct.pack('<%df' % len(pos), *pos) + struct.pack('<%df' % len(nrm), *nrm) + struct.pack('<%dI' % len(idx), *idx)
n = len(pos) // 3
variants = [
  {"pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.3, 0.2, 1], "metallicFactor": 0, "roughnessFactor": 0.35}},
  {"pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.3, 0.2, 1], "metallicFactor": 0, "roughnessFactor": 0.35}, "extensions": {"KHR_materials_ior": {"ior": 2.5}}},
  {"pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.3, 0.2, 1], "metallicFactor": 0, "roughnessFactor": 0.35}, "extensions": {"KHR_materials_specular": {"specularFactor": 0.2}}},
  {"pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.3, 0.2, 1], "metallicFactor": 0, "roughnessFactor": 0.35}, "extensions": {"KHR_materials_specular": {"specularColorFactor": [0.2, 1.0, 3.0]}, "KHR_materials_ior": {"ior": 1.8}}},
]
g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1, 2, 3]}],
     "nodes": [{"mesh": k, "translation": [2.3 * k - 3.45, 0, 0]} for k in range(4)],
     "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": k}]} for k in range(4)],
     "materials": variants,
     "extensionsUsed": ["KHR_materials_ior", "KHR_materials_specular"],
     "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
     "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 12 * n}, {"buffer": 0, "byteOffset": 12 * n, "byteLength": 12 * n},
                     {"buffer": 0, "byteOffset": 24 * n, "byteLength": 4 * len(idx)}],
     "accessors": [{"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3", "min": [-1, -1, -1], "max": [1, 1, 1]},
                   {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"},
                   {"bufferView": 2, "componentType": 5125, "count": len(idx), "type": "SCALAR"}]}
if '--plain' in sys.argv[2:]:
    for m in g["materials"]: m.pop("extensions", None)
    g.pop("extensionsUsed")
json.dump(g, open(sys.argv[1], 'w'))
