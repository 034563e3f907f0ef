#!/usr/bin/env python3
"""Writes assets/looks/looks_scene.gltf: the test and demo scene for the bake's looks
(issue 9; docs/format.md "LOOK"). An opaque box with a textured material ("box": an 8 x 8
red and cream checker PNG, embedded) sits inside a transparent sphere (material "glass",
alphaMode BLEND, a pale blue factor); a plain cube beside them has no material (a part of
its own, white) and sharp edges for crease lines. Static, Y-up, in metres.

    python3 scripts/make_looks_scene.py [OUT.gltf]

Pure standard library; the output is deterministic (same bytes every run)."""
import base64
import json
import math
import struct
import sys
import zlib


def png(width, height, pixel):
    """An RGBA8 PNG of pixel(x, y) -> (r, g, b, a)."""
    rows = b"".join(b"\0" + b"".join(bytes(pixel(x, y)) for x in range(width))
                    for y in range(height))

    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))
    header = struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) +
            chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


def box(cx, cy, cz, h):
    """24 vertices (4 per face, own normals and UVs), 12 triangles, outward."""
    pos, nrm, uv, idx = [], [], [], []
    for axis in range(3):
        for sign in (1, -1):
            n = [0, 0, 0]
            n[axis] = sign
            u_axis, v_axis = [(1, 2), (2, 0), (0, 1)][axis]
            base = len(pos)
            for du, dv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis] = sign * h
                p[u_axis] = du * h
                p[v_axis] = dv * h
                pos.append((cx + p[0], cy + p[1], cz + p[2]))
                nrm.append(tuple(float(c) for c in n))
                uv.append(((du + 1) / 2, (dv + 1) / 2))
            quad = [(0, 1, 2), (0, 2, 3)] if sign > 0 else [(0, 2, 1), (0, 3, 2)]
            for t in quad:
                idx.extend(base + k for k in t)
    return pos, nrm, uv, idx


def sphere(cx, cy, cz, r, slices=48, stacks=24):
    pos, nrm, idx = [], [], []
    for i in range(stacks + 1):
        th = math.pi * i / stacks
        for j in range(slices + 1):
            ph = 2 * math.pi * j / slices
            n = (math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph))
            nrm.append(n)
            pos.append((cx + r * n[0], cy + r * n[1], cz + r * n[2]))
    for i in range(stacks):
        for j in range(slices):
            a, b = i * (slices + 1) + j, i * (slices + 1) + j + 1
            c, d = a + slices + 1, b + slices + 1
            if i > 0:
                idx.extend((a, b, c))
            if i < stacks - 1:
                idx.extend((b, d, c))
    return pos, nrm, idx


class Buffer:
    def __init__(self):
        self.data = bytearray()
        self.views, self.accessors = [], []

    def view(self, blob):
        while len(self.data) % 4:
            self.data.append(0)
        self.views.append({"buffer": 0, "byteOffset": len(self.data), "byteLength": len(blob)})
        self.data += blob
        return len(self.views) - 1

    def floats(self, rows, kind):
        flat = [c for row in rows for c in row]
        acc = {"bufferView": self.view(struct.pack("<%df" % len(flat), *flat)),
               "componentType": 5126, "count": len(rows), "type": kind}
        if kind == "VEC3":
            acc["min"] = [min(r[k] for r in rows) for k in range(3)]
            acc["max"] = [max(r[k] for r in rows) for k in range(3)]
        self.accessors.append(acc)
        return len(self.accessors) - 1

    def indices(self, idx):
        self.accessors.append({"bufferView": self.view(struct.pack("<%dI" % len(idx), *idx)),
                               "componentType": 5125, "count": len(idx), "type": "SCALAR"})
        return len(self.accessors) - 1


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "assets/looks/looks_scene.gltf"
    buf = Buffer()
    bp, bn, bu, bi = box(0, 0.3, 0, 0.25)
    sp, sn, si = sphere(0, 0.3, 0, 0.55)
    cp, cn, _, ci = box(1.1, 0.2, 0, 0.2)
    checker = png(64, 64, lambda x, y: (200, 40, 30, 255) if (x // 8 + y // 8) % 2 == 0
                  else (240, 225, 190, 255))
    box_prim = {"attributes": {"POSITION": buf.floats(bp, "VEC3"), "NORMAL": buf.floats(bn, "VEC3"),
                               "TEXCOORD_0": buf.floats(bu, "VEC2")},
                "indices": buf.indices(bi), "material": 0}
    sphere_prim = {"attributes": {"POSITION": buf.floats(sp, "VEC3"),
                                  "NORMAL": buf.floats(sn, "VEC3")},
                   "indices": buf.indices(si), "material": 1}
    cube_prim = {"attributes": {"POSITION": buf.floats(cp, "VEC3"),
                                "NORMAL": buf.floats(cn, "VEC3")},
                 "indices": buf.indices(ci)}
    image_view = buf.view(checker)
    gltf = {
        "asset": {"version": "2.0", "generator": "scripts/make_looks_scene.py"},
        "scene": 0, "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [{"name": "box", "mesh": 0}, {"name": "glass", "mesh": 1},
                  {"name": "cube", "mesh": 2}],
        "meshes": [{"name": "box", "primitives": [box_prim]},
                   {"name": "glass_sphere", "primitives": [sphere_prim]},
                   {"name": "plain_cube", "primitives": [cube_prim]}],
        "materials": [
            {"name": "box_checker", "pbrMetallicRoughness":
                {"baseColorTexture": {"index": 0}, "metallicFactor": 0}},
            {"name": "glass", "alphaMode": "BLEND", "pbrMetallicRoughness":
                {"baseColorFactor": [0.6, 0.8, 1.0, 0.25], "metallicFactor": 0}}],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{"wrapS": 10497, "wrapT": 10497}],
        "images": [{"bufferView": image_view, "mimeType": "image/png"}],
        "buffers": [{"byteLength": len(buf.data), "uri": "data:application/octet-stream;base64," +
                     base64.b64encode(bytes(buf.data)).decode("ascii")}],
        "bufferViews": buf.views,
        "accessors": buf.accessors,
    }
    with open(out, "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
