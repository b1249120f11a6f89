#!/usr/bin/env python3
# Writes a glTF of four spheres in a row, one material extension's sweep (for
# scripts/compare-threejs.sh):
#   specular:  dielectrics of one base colour: plain, KHR_materials_ior 2.5, KHR_materials_specular
#              factor 0.2, and ior 1.8 with a tinted specularColorFactor;
#   clearcoat: KHR_materials_clearcoat over a rough red dielectric (coat roughness 0 and 0.3), over
#              a rough blue metal, and at weight 0.5 over a smooth gold.
# Usage: scripts/make-material-spheres.py SET OUT.gltf [--plain: without the extensions]
import base64
import json
import math
import struct
import sys
sweep, out = sys.argv[1], sys.argv[2]
# A UV sphere (radius 1), four spheres with the set's materials.
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
def pbr(colour, metallic, roughness):
    return {"baseColorFactor": colour + [1], "metallicFactor": metallic, "roughnessFactor": roughness}
def coat(weight, roughness):
    return {"KHR_materials_clearcoat": {"clearcoatFactor": weight, "clearcoatRoughnessFactor": roughness}}
sets = {"specular": [
  {"pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.3, 0.2, 1], "metallicFactor": 0, "roughnessFactor": 0.35}},
  {"pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.3, 0.2, 1], "metallicFactor": 0, "roughnessFactor": 0.35}, "extensions": {"KHR_materials_ior": {"ior": 2.5}}},
  {"pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.3, 0.2, 1], "metallicFactor": 0, "roughnessFactor": 0.35}, "extensions": {"KHR_materials_specular": {"specularFactor": 0.2}}},
  {"pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.3, 0.2, 1], "metallicFactor": 0, "roughnessFactor": 0.35}, "extensions": {"KHR_materials_specular": {"specularColorFactor": [0.2, 1.0, 3.0]}, "KHR_materials_ior": {"ior": 1.8}}},
], "clearcoat": [
  {"pbrMetallicRoughness": pbr([0.7, 0.05, 0.05], 0, 0.7), "extensions": coat(1.0, 0.0)},
  {"pbrMetallicRoughness": pbr([0.7, 0.05, 0.05], 0, 0.7), "extensions": coat(1.0, 0.3)},
  {"pbrMetallicRoughness": pbr([0.1, 0.2, 0.6], 1, 0.6), "extensions": coat(1.0, 0.05)},
  {"pbrMetallicRoughness": pbr([1.0, 0.78, 0.34], 1, 0.2), "extensions": coat(0.5, 0.1)},
]}
variants = sets[sweep]
used = sorted({name for m in variants for name in m.get("extensions", {})})
g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1, 2, 3]}],
     "nodes": [{"mesh": k, "translation": [2.3 * k - 3.45, 0, 0]} for k in range(4)],
     "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": k}]} for k in range(4)],
     "materials": variants,
     "extensionsUsed": used,
     "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
     "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 12 * n}, {"buffer": 0, "byteOffset": 12 * n, "byteLength": 12 * n},
                     {"buffer": 0, "byteOffset": 24 * n, "byteLength": 4 * len(idx)}],
     "accessors": [{"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3", "min": [-1, -1, -1], "max": [1, 1, 1]},
                   {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"},
                   {"bufferView": 2, "componentType": 5125, "count": len(idx), "type": "SCALAR"}]}
if '--plain' in sys.argv[3:]:
    for m in g["materials"]: m.pop("extensions", None)
    g.pop("extensionsUsed")
json.dump(g, open(out, 'w'))
