#!/usr/bin/env python3
# Writes a glTF of four spheres in a row, one material extension's sweep (for
# scripts/compare-threejs.sh):
#   specular:  dielectrics of one base colour: plain, KHR_materials_ior 2.5, KHR_materials_specular
#              factor 0.2, and ior 1.8 with a tinted specularColorFactor;
#   clearcoat: KHR_materials_clearcoat over a rough red dielectric (coat roughness 0 and 0.3), over
#              a rough blue metal, and at weight 0.5 over a smooth gold.
#   sheen:     KHR_materials_sheen: a white sheen of roughness 0.3 and 0.8 over a dark red
#              dielectric, a blue sheen over a rough white one, a sheen over a rough gold metal;
#   addressing: maps at their own addresses (TEXCOORD_0 and _1, KHR_texture_transform per map,
#              wrapS and wrapT apart): an emissive stripe map on TEXCOORD_1 over a checker base;
#              the checker scaled by its transform over an unscaled roughness map; a checker
#              repeating in u and clamped in v; an occlusion map on TEXCOORD_1 (sky light only).
# Usage: scripts/make-material-spheres.py SET OUT.gltf [--plain: without the extensions; for
# addressing, every map on TEXCOORD_0 without transform or sampler]
import base64
import json
import math
import struct
import sys
import zlib
sweep, out = sys.argv[1], sys.argv[2]
# A UV sphere (radius 1), four spheres with the set's materials.
st, sl = 48, 24
pos, nrm, idx, uv0, uv1 = [], [], [], [], []
for i in range(sl + 1):
    th = math.pi * i / sl
    for j in range(st + 1):
        ph = 2 * math.pi * j / st
        x, y, z = math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph)
        pos += [x, y, z]; nrm += [x, y, z]
        uv0 += [j / st, i / sl]; uv1 += [i / sl, 2 * j / st]  # set 1: v along the equator, twice round
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
def sheen(colour, roughness):
    return {"KHR_materials_sheen": {"sheenColorFactor": colour, "sheenRoughnessFactor": roughness}}
sets["sheen"] = [
  {"pbrMetallicRoughness": pbr([0.3, 0.02, 0.02], 0, 0.8), "extensions": sheen([1, 1, 1], 0.3)},
  {"pbrMetallicRoughness": pbr([0.3, 0.02, 0.02], 0, 0.8), "extensions": sheen([1, 1, 1], 0.8)},
  {"pbrMetallicRoughness": pbr([0.8, 0.8, 0.8], 0, 0.9), "extensions": sheen([0.1, 0.3, 1.0], 0.5)},
  {"pbrMetallicRoughness": pbr([1.0, 0.78, 0.34], 1, 0.5), "extensions": sheen([0.6, 0.6, 0.6], 0.4)},
]
def png(w, h, texel):  # an RGBA PNG, texel(x, y) -> (r, g, b, a), top row first
    raw = b''.join(b'\0' + bytes(c for x in range(w) for c in texel(x, y)) for y in range(h))
    chunk = lambda t, d: struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d) & 0xffffffff)
    return b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 6, 0, 0, 0)) + chunk(b'IDAT', zlib.compress(raw)) + chunk(b'IEND', b'')
def transform(**t):
    return {"extensions": {"KHR_texture_transform": t}}
sets["addressing"] = [
  {"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0, "roughnessFactor": 0.6},
   "emissiveTexture": {"index": 1, "texCoord": 1}, "emissiveFactor": [0.6, 0.6, 0.6]},
  {"pbrMetallicRoughness": {"baseColorTexture": dict({"index": 0}, **transform(scale=[4, 2], offset=[0.25, 0])),
                            "metallicRoughnessTexture": {"index": 2}, "metallicFactor": 1, "roughnessFactor": 1}},
  {"pbrMetallicRoughness": {"baseColorTexture": dict({"index": 3}, **transform(scale=[3, 3], offset=[-1, -1])),
                            "metallicFactor": 0, "roughnessFactor": 0.5}},
  {"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0, "roughnessFactor": 0.4},
   "occlusionTexture": {"index": 1, "texCoord": 1}},
]
images = [png(64, 64, lambda x, y: (230, 200, 60, 255) if (x // 8 + y // 8) % 2 else (40, 70, 160, 255)),    # checker
          png(64, 8, lambda x, y: (255, 80, 30, 255) if (x // 8) % 2 else (0, 0, 0, 255)),                 # stripes
          png(16, 16, lambda x, y: (0, 40 + 13 * x, 255 * (y // 8), 255)),                                  # roughness / metal
          png(64, 64, lambda x, y: (200, 60, 60, 255) if (x // 16 + y // 16) % 2 else (240, 240, 240, 255))]  # checker, coarse
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
if sweep == "addressing":
    n0 = len(blob)
    blob += struct.pack('<%df' % len(uv0), *uv0) + struct.pack('<%df' % len(uv1), *uv1)
    g["bufferViews"] += [{"buffer": 0, "byteOffset": n0, "byteLength": 8 * n}, {"buffer": 0, "byteOffset": n0 + 8 * n, "byteLength": 8 * n}]
    g["accessors"] += [{"bufferView": 3, "componentType": 5126, "count": n, "type": "VEC2"},
                       {"bufferView": 4, "componentType": 5126, "count": n, "type": "VEC2"}]
    g["buffers"][0] = {"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}
    for m in g["meshes"]: m["primitives"][0]["attributes"].update({"TEXCOORD_0": 3, "TEXCOORD_1": 4})
    g["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(i).decode()} for i in images]
    g["samplers"] = [{"wrapS": 10497, "wrapT": 33071}]
    g["textures"] = [{"source": 0}, {"source": 1}, {"source": 2}, {"source": 3, "sampler": 0}]
    g["extensionsUsed"] = ["KHR_texture_transform"]
    if '--plain' in sys.argv[3:]:
        g["textures"][3].pop("sampler")
        for m in g["materials"]:
            for ref in [m.get("emissiveTexture"), m.get("occlusionTexture")] + list(m["pbrMetallicRoughness"].values()):
                if isinstance(ref, dict): ref.pop("extensions", None); ref.pop("texCoord", None)
elif '--plain' in sys.argv[3:]:
    for m in g["materials"]: m.pop("extensions", None)
    g.pop("extensionsUsed")
json.dump(g, open(out, 'w'))
