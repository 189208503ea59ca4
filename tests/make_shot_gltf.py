#!/usr/bin/env python3
"""Writes a glTF shot for tests/cli_shot_test.sh: a camera node 'ShotCam' (camera 'Camera.001')
at (0, 0, D) looking down -z with vertical field of view YFOV and aspect ratio ASPECT, and at
z = 0, exactly filling its frame, a checker of COLUMNS x ROWS cells (node 'Board', two
materials), plus a small box 'Probe' at z = -Z_PROBE on the axis, partly hidden.

Usage: make_shot_gltf.py OUT.gltf D YFOV ASPECT COLUMNS ROWS [--second-camera]"""
import base64, json, math, struct, sys

out, d, yfov, aspect, columns, rows = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), \
    float(sys.argv[4]), int(sys.argv[5]), int(sys.argv[6])
half_h = d * math.tan(yfov / 2)
half_w = half_h * aspect
positions, indices = {0: [], 1: []}, {0: [], 1: []}
for j in range(rows):
    for i in range(columns):
        m = (i + j) % 2
        x0 = -half_w + 2 * half_w * i / columns
        x1 = -half_w + 2 * half_w * (i + 1) / columns
        y0 = -half_h + 2 * half_h * j / rows
        y1 = -half_h + 2 * half_h * (j + 1) / rows
        # Outer cells reach a little past the frame so that no background shows at its edges.
        grow = 0.02 * half_w
        x0 -= grow if i == 0 else 0
        x1 += grow if i == columns - 1 else 0
        y0 -= grow if j == 0 else 0
        y1 += grow if j == rows - 1 else 0
        base = len(positions[m])
        positions[m] += [(x0, y0, 0), (x1, y0, 0), (x1, y1, 0), (x0, y1, 0)]
        indices[m] += [base, base + 1, base + 2, base, base + 2, base + 3]
blob = b""
views, accessors, meshes = [], [], []
for m in (0, 1):
    p = b"".join(struct.pack("<3f", *v) for v in positions[m])
    ix = b"".join(struct.pack("<I", k) for k in indices[m])
    lo = [min(v[a] for v in positions[m]) for a in range(3)]
    hi = [max(v[a] for v in positions[m]) for a in range(3)]
    views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(p)})
    blob += p
    views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(ix)})
    blob += ix
    accessors.append({"bufferView": len(views) - 2, "componentType": 5126,
                      "count": len(positions[m]), "type": "VEC3", "min": lo, "max": hi})
    accessors.append({"bufferView": len(views) - 1, "componentType": 5125,
                      "count": len(indices[m]), "type": "SCALAR"})
    meshes.append({"primitives": [{"attributes": {"POSITION": len(accessors) - 2},
                                   "indices": len(accessors) - 1, "material": m}]})
gltf = {
    "asset": {"version": "2.0"}, "scene": 0,
    "scenes": [{"nodes": [0, 1, 2]}],
    "nodes": [
        {"name": "Board", "children": [3, 4]},
        {"name": "ShotCam", "camera": 0, "translation": [0, 0, d]},
        {"name": "Probe", "mesh": 0, "translation": [0, 0, -0.5 * d], "scale": [0.01, 0.01, 0.01]},
        {"mesh": 0}, {"mesh": 1}],
    "cameras": [{"name": "Camera.001", "type": "perspective",
                 "perspective": {"yfov": yfov, "aspectRatio": aspect, "znear": 0.1}}],
    "materials": [{"name": "white", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1],
                                                            "metallicFactor": 0}},
                  {"name": "black", "pbrMetallicRoughness": {"baseColorFactor": [0.05, 0.05, 0.05, 1],
                                                            "metallicFactor": 0}}],
    "meshes": meshes, "accessors": accessors, "bufferViews": views,
    "buffers": [{"byteLength": len(blob),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
}
json.dump(gltf, open(out, "w"))
