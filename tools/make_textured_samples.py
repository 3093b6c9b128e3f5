#!/usr/bin/env python3
"""Writes the project's own textured and coloured sample meshes into
data/textured/ (Python's standard library only; the same bytes on every run):

  die.obj, die.mtl, die.png   a die: a cube whose faces are 12 x 12 grids of
                              triangles, textured from a 3 x 2 atlas of
                              coloured faces with their pips (map_Kd with
                              options); every cube edge is a UV seam
  ring.glb                    a torus in two primitives sharing their border:
                              one textured (an embedded PNG, a checker with a
                              hue ramp, KHR_texture_transform), one with
                              COLOR_0; under two nodes (rotation, scale,
                              translation)
  hue_ball.ply                a bumpy sphere (icosphere, 3 subdivisions),
                              binary PLY with uchar RGBA colours by direction

Usage: python3 tools/make_textured_samples.py [OUT_DIR]  (default data/textured)
"""
import json
import math
import os
import struct
import sys
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "data", "textured")


def png_bytes(width, height, rgb_rows):
    """An 8-bit RGB PNG from rows of (r, g, b) tuples."""
    raw = b"".join(b"\x00" + bytes(c for px in row for c in px) for row in rgb_rows)

    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))

    return (b"\x89PNG\r\n\x1a\n" +
            chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def hsv(h, s, v):
    i = int(h * 6) % 6
    f = h * 6 - math.floor(h * 6)
    p, q, t = v * (1 - s), v * (1 - f * s), v * (1 - (1 - f) * s)
    r, g, b = [(v, t, p), (q, v, p), (p, v, t), (p, q, v), (t, p, v), (v, p, q)][i]
    return (round(r * 255), round(g * 255), round(b * 255))


# ---- die.obj, die.mtl, die.png ----

TILE = 64  # pixels per die face in the atlas
PIPS = {  # pip centres in a face's unit square, by number
    1: [(0.5, 0.5)],
    2: [(0.25, 0.25), (0.75, 0.75)],
    3: [(0.25, 0.25), (0.5, 0.5), (0.75, 0.75)],
    4: [(0.25, 0.25), (0.75, 0.25), (0.25, 0.75), (0.75, 0.75)],
    5: [(0.25, 0.25), (0.75, 0.25), (0.5, 0.5), (0.25, 0.75), (0.75, 0.75)],
    6: [(0.25, 0.2), (0.75, 0.2), (0.25, 0.5), (0.75, 0.5), (0.25, 0.8), (0.75, 0.8)],
}


def die_atlas():
    """3 x 2 tiles: number n at column (n - 1) % 3, row (n - 1) // 3."""
    width, height = 3 * TILE, 2 * TILE
    rows = []
    for y in range(height):
        row = []
        for x in range(width):
            n = (y // TILE) * 3 + x // TILE + 1
            fx, fy = (x % TILE + 0.5) / TILE, (y % TILE + 0.5) / TILE
            colour = hsv((n - 1) / 6.0, 0.35, 1.0)  # a pastel per face
            if min(fx, fy, 1 - fx, 1 - fy) < 0.06:
                colour = hsv((n - 1) / 6.0, 0.9, 0.55)  # its darker border
            for cx, cy in PIPS[n]:
                if (fx - cx) ** 2 + (fy - cy) ** 2 < 0.09 ** 2:
                    colour = (25, 25, 40)
            row.append(colour)
        rows.append(row)
    return png_bytes(width, height, rows)


# Faces of the cube: (number, origin, u axis, v axis), the axes spanning the
# face as seen from outside, v pointing down the image; opposite faces sum
# to 7.
CUBE = [
    (1, (-1, 1, 1), (1, 0, 0), (0, -1, 0)),     # +z
    (6, (1, 1, -1), (-1, 0, 0), (0, -1, 0)),    # -z
    (2, (1, 1, 1), (0, 0, -1), (0, -1, 0)),     # +x
    (5, (-1, 1, -1), (0, 0, 1), (0, -1, 0)),    # -x
    (3, (-1, 1, -1), (1, 0, 0), (0, 0, 1)),     # +y
    (4, (-1, -1, 1), (1, 0, 0), (0, 0, -1)),    # -y
]


def die_obj(grid=12):
    v_lines, vt_lines, f_lines = [], [], []
    for number, origin, ua, va in CUBE:
        col, row = (number - 1) % 3, (number - 1) // 3
        base = len(v_lines)
        for j in range(grid + 1):
            for i in range(grid + 1):
                s, t = i / grid, j / grid
                p = [origin[k] + 2 * s * ua[k] + 2 * t * va[k] for k in range(3)]
                v_lines.append("v %.4f %.4f %.4f" % tuple(p))
                # glTF-style (u, v down) in the atlas, written OBJ-style (v up).
                u, v = (col + s) / 3.0, (row + t) / 2.0
                vt_lines.append("vt %.5f %.5f" % (u, 1.0 - v))
        for j in range(grid):
            for i in range(grid):
                a = base + j * (grid + 1) + i + 1  # 1-based, v and vt alike
                b, c, d = a + 1, a + grid + 1, a + grid + 2
                # u right and v down, seen from outside: (a, c, b) winds
                # counter-clockwise.
                f_lines.append("f %d/%d %d/%d %d/%d" % (a, a, c, c, b, b))
                f_lines.append("f %d/%d %d/%d %d/%d" % (b, b, c, c, d, d))
    text = ["# A die: tools/make_textured_samples.py", "mtllib die.mtl"]
    text += v_lines + vt_lines + ["usemtl die"] + f_lines
    return "\n".join(text) + "\n"


DIE_MTL = """# tools/make_textured_samples.py
newmtl die
Kd 1.000 1.000 1.000
Ks 0.000 0.000 0.000
map_Kd -clamp on die.png
"""


# ---- ring.glb ----

def ring_glb(major=48, minor=24, radius=1.0, tube=0.35):
    """Two primitives: the half with u < 0.5 textured, the other coloured."""
    def vertex(i, j):
        a, b = 2 * math.pi * i / major, 2 * math.pi * j / minor
        return ((radius + tube * math.cos(b)) * math.cos(a),
                (radius + tube * math.cos(b)) * math.sin(a), tube * math.sin(b))

    halves = [range(0, major // 2 + 1), range(major // 2, major + 1)]
    prims = []
    for h, columns in enumerate(halves):
        columns = list(columns)
        pos, uv, col, idx = [], [], [], []
        for i in columns:
            for j in range(minor + 1):
                pos.append(vertex(i % major, j % minor))
                uv.append((i / major, j / minor))
                col.append(hsv(i / major, 0.8, 1.0) + (255,))
        rows = minor + 1
        for ci in range(len(columns) - 1):
            for j in range(minor):
                a = ci * rows + j
                b, c, d = a + 1, a + rows, a + rows + 1
                idx += [a, c, b, b, c, d]
        prims.append((pos, uv, col, idx))

    texture_rows = []
    for y in range(64):
        row = []
        for x in range(128):
            check = ((x // 16) + (y // 16)) % 2
            row.append(hsv(x / 128.0, 0.75 if check else 0.35, 0.95 if check else 0.6))
        texture_rows.append(row)
    png = png_bytes(128, 64, texture_rows)

    blob = bytearray()
    views, accessors = [], []

    def add_view(data, target=None):
        while len(blob) % 4:
            blob.append(0)
        view = {"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)}
        if target:
            view["target"] = target
        blob.extend(data)
        views.append(view)
        return len(views) - 1

    def add_accessor(view, component, count, kind, **extra):
        accessors.append(dict(bufferView=view, componentType=component,
                              count=count, type=kind, **extra))
        return len(accessors) - 1

    meshes_prims = []
    for h, (pos, uv, col, idx) in enumerate(prims):
        lo = [min(p[k] for p in pos) for k in range(3)]
        hi = [max(p[k] for p in pos) for k in range(3)]
        p_acc = add_accessor(add_view(b"".join(struct.pack("<3f", *p) for p in pos), 34962),
                             5126, len(pos), "VEC3",
                             min=[struct.unpack("<f", struct.pack("<f", x))[0] for x in lo],
                             max=[struct.unpack("<f", struct.pack("<f", x))[0] for x in hi])
        i_acc = add_accessor(add_view(b"".join(struct.pack("<H", i) for i in idx), 34963),
                             5123, len(idx), "SCALAR")
        attributes = {"POSITION": p_acc}
        if h == 0:
            attributes["TEXCOORD_0"] = add_accessor(
                add_view(b"".join(struct.pack("<2f", *t) for t in uv), 34962),
                5126, len(uv), "VEC2")
        else:
            attributes["COLOR_0"] = add_accessor(
                add_view(b"".join(struct.pack("<4B", *c) for c in col), 34962),
                5121, len(col), "VEC4", normalized=True)
        meshes_prims.append({"attributes": attributes, "indices": i_acc, "material": h})
    image_view = add_view(png)
    while len(blob) % 4:
        blob.append(0)

    gltf = {
        "asset": {"version": "2.0", "generator": "tools/make_textured_samples.py"},
        "extensionsUsed": ["KHR_texture_transform"],
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [
            {"name": "stand", "rotation": [0.7071068, 0, 0, 0.7071068],
             "scale": [0.5, 0.5, 0.5], "children": [1]},
            {"name": "ring", "translation": [0, 0, 0.25], "mesh": 0},
        ],
        "meshes": [{"name": "ring", "primitives": meshes_prims}],
        "materials": [
            {"name": "checker", "pbrMetallicRoughness": {
                "baseColorTexture": {"index": 0, "extensions": {
                    "KHR_texture_transform": {"scale": [2, 1]}}},
                "metallicFactor": 0.0, "roughnessFactor": 0.8}},
            {"name": "painted", "pbrMetallicRoughness": {
                "metallicFactor": 0.0, "roughnessFactor": 0.5}},
        ],
        "textures": [{"sampler": 0, "source": 0}],
        "samplers": [{"wrapS": 10497, "wrapT": 10497}],
        "images": [{"name": "checker", "bufferView": image_view, "mimeType": "image/png"}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob)}],
    }
    text = json.dumps(gltf, separators=(",", ":")).encode()
    text += b" " * ((4 - len(text) % 4) % 4)
    total = 12 + 8 + len(text) + 8 + len(blob)
    return (struct.pack("<4sII", b"glTF", 2, total) +
            struct.pack("<I4s", len(text), b"JSON") + text +
            struct.pack("<I4s", len(blob), b"BIN\x00") + bytes(blob))


# ---- hue_ball.ply ----

def icosphere(levels):
    t = (1 + 5 ** 0.5) / 2
    verts = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
             (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9),
             (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2),
             (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10),
             (8, 6, 7), (9, 8, 1)]
    verts = [tuple(c / math.sqrt(sum(x * x for x in v)) for c in v) for v in verts]
    for _ in range(levels):
        midpoint = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in midpoint:
                m = [(verts[a][k] + verts[b][k]) / 2 for k in range(3)]
                n = math.sqrt(sum(x * x for x in m))
                verts.append(tuple(x / n for x in m))
                midpoint[key] = len(verts) - 1
            return midpoint[key]

        new = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            new += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = new
    return verts, faces


def hue_ball_ply():
    verts, faces = icosphere(3)
    header = ("ply\nformat binary_little_endian 1.0\n"
              "comment tools/make_textured_samples.py\n"
              "element vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
              "property uchar red\nproperty uchar green\nproperty uchar blue\n"
              "property uchar alpha\nelement face %d\n"
              "property list uchar int vertex_indices\nend_header\n" % (len(verts), len(faces)))
    body = bytearray()
    for x, y, z in verts:
        bump = 1 + 0.12 * math.sin(3 * math.atan2(y, x)) * math.cos(2 * z)
        hue = (math.atan2(y, x) / (2 * math.pi)) % 1.0
        r, g, b = hsv(hue, 0.5 + 0.45 * z * z, 0.6 + 0.4 * (z + 1) / 2)
        body += struct.pack("<3f4B", x * bump, y * bump, z * bump, r, g, b, 255)
    for f in faces:
        body += struct.pack("<B3i", 3, *f)
    return header.encode() + bytes(body)


def main():
    os.makedirs(OUT, exist_ok=True)
    files = {
        "die.png": die_atlas(),
        "die.obj": die_obj().encode(),
        "die.mtl": DIE_MTL.encode(),
        "ring.glb": ring_glb(),
        "hue_ball.ply": hue_ball_ply(),
    }
    for name, data in files.items():
        with open(os.path.join(OUT, name), "wb") as f:
            f.write(data)
        print("%-14s %7d bytes" % (name, len(data)))


if __name__ == "__main__":
    main()
