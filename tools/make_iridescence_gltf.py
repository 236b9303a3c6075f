#!/usr/bin/env python3
"""Writes examples/iridescent_spheres.gltf: a small glTF 2.0 sample for KHR_materials_iridescence.

Three UV spheres (one mesh's accessors shared by three meshes, each with its own material) on a row:
  left   - iridescenceFactor 1, IOR 1.3, thickness 100-400 nm, no texture (thickness = maximum, 400 nm)
  middle - iridescenceFactor 1, IOR 1.3, thickness 200-800 nm, a thickness texture whose G channel runs
           from 0 at the top to 1 at the bottom (a draining film), embedded as a PNG data URI
  right  - iridescenceFactor 0.5 over a red dielectric base, thickness 300-300 nm
and a grey floor quad without iridescence. Everything is embedded (base64 data URIs), so the file stands
alone. Only the Python standard library is used. Run from the repository root:

    python3 tools/make_iridescence_gltf.py
"""
import base64
import json
import math
import struct
import zlib

SEG, RINGS = 48, 24


def sphere():
    pos, nrm, uv, idx = [], [], [], []
    for r in range(RINGS + 1):
        v = r / RINGS
        th = v * math.pi
        for s in range(SEG + 1):
            u = s / SEG
            ph = u * 2 * math.pi
            n = (math.sin(th) * math.sin(ph), math.cos(th), math.sin(th) * math.cos(ph))
            pos += n
            nrm += n
            uv += (u, v)
    for r in range(RINGS):
        for s in range(SEG):
            a = r * (SEG + 1) + s
            b = a + SEG + 1
            idx += (a, b, a + 1, a + 1, b, b + 1)
    return pos, nrm, uv, idx


def png_gradient(w=4, h=64):
    """An RGB PNG whose G channel grows from 0 (top row) to 255 (bottom row)."""
    raw = b""
    for y in range(h):
        g = round(255 * y / (h - 1))
        raw += b"\x00" + bytes((0, g, 0)) * w
    def chunk(t, d):
        c = t + d
        return struct.pack(">I", len(d)) + c + struct.pack(">I", zlib.crc32(c) & 0xFFFFFFFF)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def main():
    pos, nrm, uv, idx = sphere()
    quad_pos = [-4, 0, -3, 4, 0, -3, 4, 0, 3, -4, 0, 3]
    quad_nrm = [0, 1, 0] * 4
    quad_idx = [0, 2, 1, 0, 3, 2]
    blobs, views, accessors = [], [], []

    def add(data, fmt, count, typ, comp, target, minmax=None):
        b = struct.pack("<%d%s" % (len(data), fmt), *data)
        off = sum(len(x) for x in blobs)
        blobs.append(b + b"\x00" * ((4 - len(b) % 4) % 4))
        views.append({"buffer": 0, "byteOffset": off, "byteLength": len(b), "target": target})
        acc = {"bufferView": len(views) - 1, "componentType": comp, "count": count, "type": typ}
        if minmax:
            acc["min"], acc["max"] = minmax
        accessors.append(acc)
        return len(accessors) - 1

    nv = len(pos) // 3
    a_pos = add(pos, "f", nv, "VEC3", 5126, 34962, ([-1, -1, -1], [1, 1, 1]))
    a_nrm = add(nrm, "f", nv, "VEC3", 5126, 34962)
    a_uv = add(uv, "f", nv, "VEC2", 5126, 34962)
    a_idx = add(idx, "I", len(idx), "SCALAR", 5125, 34963)
    q_pos = add(quad_pos, "f", 4, "VEC3", 5126, 34962, ([-4, 0, -3], [4, 0, 3]))
    q_nrm = add(quad_nrm, "f", 4, "VEC3", 5126, 34962)
    q_idx = add(quad_idx, "I", 6, "SCALAR", 5125, 34963)
    buf = b"".join(blobs)
    png = base64.b64encode(png_gradient()).decode()

    def irid(factor, dmin, dmax, tex=None):
        e = {"iridescenceFactor": factor, "iridescenceIor": 1.3,
             "iridescenceThicknessMinimum": dmin, "iridescenceThicknessMaximum": dmax}
        if tex is not None:
            e["iridescenceThicknessTexture"] = {"index": tex}
        return {"KHR_materials_iridescence": e}

    materials = [
        {"name": "film 100-400 nm (no texture: 400 nm)", "extensions": irid(1.0, 100, 400),
         "pbrMetallicRoughness": {"baseColorFactor": [0.02, 0.02, 0.02, 1], "metallicFactor": 0, "roughnessFactor": 0.4}},
        {"name": "film 200-800 nm, draining texture", "extensions": irid(1.0, 200, 800, 0),
         "pbrMetallicRoughness": {"baseColorFactor": [0.02, 0.02, 0.02, 1], "metallicFactor": 0, "roughnessFactor": 0.4}},
        {"name": "half film 300 nm over red", "extensions": irid(0.5, 300, 300),
         "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.05, 0.04, 1], "metallicFactor": 0, "roughnessFactor": 0.3}},
        {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0, "roughnessFactor": 1}},
    ]
    prim = {"attributes": {"POSITION": a_pos, "NORMAL": a_nrm, "TEXCOORD_0": a_uv}, "indices": a_idx}
    meshes = [{"name": "sphere %d" % i, "primitives": [dict(prim, material=i)]} for i in range(3)]
    meshes.append({"name": "floor", "primitives": [{"attributes": {"POSITION": q_pos, "NORMAL": q_nrm},
                                                      "indices": q_idx, "material": 3}]})
    nodes = [{"mesh": i, "translation": [2.3 * (i - 1), 1, 0]} for i in range(3)] + [{"mesh": 3}]
    gltf = {
        "asset": {"version": "2.0", "generator": "iridis tools/make_iridescence_gltf.py"},
        "extensionsUsed": ["KHR_materials_iridescence"],
        "scene": 0, "scenes": [{"nodes": [0, 1, 2, 3]}], "nodes": nodes, "meshes": meshes,
        "materials": materials,
        "textures": [{"source": 0}],
        "images": [{"uri": "data:image/png;base64," + png}],
        "buffers": [{"byteLength": len(buf), "uri": "data:application/octet-stream;base64," + base64.b64encode(buf).decode()}],
        "bufferViews": views, "accessors": accessors,
    }
    with open("examples/iridescent_spheres.gltf", "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")
    print("wrote examples/iridescent_spheres.gltf (%d bytes of geometry)" % len(buf))


if __name__ == "__main__":
    main()
