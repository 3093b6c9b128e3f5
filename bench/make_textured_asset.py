#!/usr/bin/env python3
"""Makes a textured asset from a binary PLY mesh, for the textured-ingest figure
(docs/BENCHMARKS.md, "Textured ingest"): OUT/NAME.obj with one UV per vertex
(a spherical projection about the bounding box's centre), OUT/NAME.mtl naming
OUT/NAME.png, a SIZE x SIZE RGB texture of smooth colour bands with a fine
checker (so that baking has detail to keep at every scale).

Usage: bench/make_textured_asset.py MESH.ply OUT_DIR [SIZE]   (default 4096)
Reads binary little-endian PLY with float x, y, z and a uchar-counted int
face list (the shared meshes' layout); nothing else is needed than Python.
"""
import math
import os
import struct
import sys
import zlib


def read_ply(path):
    with open(path, 'rb') as f:
        data = f.read()
    end = data.index(b'end_header\n') + len(b'end_header\n')
    header = data[:end].decode('ascii').splitlines()
    if 'format binary_little_endian 1.0' not in header:
        sys.exit(f'{path}: not a binary little-endian PLY')
    vertices = faces = 0
    vertex_props = []
    element = None
    for line in header:
        words = line.split()
        if words[:1] == ['element']:
            element = words[1]
            if element == 'vertex':
                vertices = int(words[2])
            elif element == 'face':
                faces = int(words[2])
        elif words[:1] == ['property'] and element == 'vertex':
            vertex_props.append(words[1])
    if vertex_props != ['float'] * 3:
        sys.exit(f'{path}: vertices must be float x, y, z only (got {vertex_props})')
    at = end
    xyz = struct.unpack_from(f'<{3 * vertices}f', data, at)
    at += 12 * vertices
    tris = []
    for _ in range(faces):
        n = data[at]
        if n != 3:
            sys.exit(f'{path}: a face with {n} corners (triangles only)')
        tris.append(struct.unpack_from('<3i', data, at + 1))
        at += 13
    return [xyz[3 * i:3 * i + 3] for i in range(vertices)], tris


def write_png(path, size):
    def chunk(kind, body):
        c = struct.pack('>I', len(body)) + kind + body
        return c + struct.pack('>I', zlib.crc32(kind + body) & 0xffffffff)

    rows = []
    for y in range(size):
        row = bytearray(1 + 3 * size)  # filter byte 0, then RGB
        v = y / size
        for x in range(size):
            u = x / size
            checker = 40 if ((x >> 4) ^ (y >> 4)) & 1 else 0
            r = int(127 + 100 * math.sin(6.2832 * 3 * u)) + checker
            g = int(127 + 100 * math.sin(6.2832 * 2 * v + 1.0)) + checker
            b = int(127 + 100 * math.cos(6.2832 * (u + v))) - checker
            i = 1 + 3 * x
            row[i] = max(0, min(255, r))
            row[i + 1] = max(0, min(255, g))
            row[i + 2] = max(0, min(255, b))
        rows.append(bytes(row))
    raw = b''.join(rows)
    png = (b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', size, size, 8, 2, 0, 0, 0)) +
           chunk(b'IDAT', zlib.compress(raw, 6)) + chunk(b'IEND', b''))
    with open(path, 'wb') as f:
        f.write(png)


def main():
    if len(sys.argv) not in (3, 4) or sys.argv[1] in ('-h', '--help'):
        print(__doc__)
        sys.exit(0 if len(sys.argv) > 1 and sys.argv[1] in ('-h', '--help') else 2)
    mesh, out = sys.argv[1], sys.argv[2]
    size = int(sys.argv[3]) if len(sys.argv) == 4 else 4096
    name = os.path.splitext(os.path.basename(mesh))[0] + '_textured'
    os.makedirs(out, exist_ok=True)
    positions, tris = read_ply(mesh)
    lo = [min(p[a] for p in positions) for a in range(3)]
    hi = [max(p[a] for p in positions) for a in range(3)]
    centre = [(lo[a] + hi[a]) / 2 for a in range(3)]
    with open(os.path.join(out, name + '.mtl'), 'w') as f:
        f.write(f'newmtl surface\nKd 1 1 1\nmap_Kd {name}.png\n')
    with open(os.path.join(out, name + '.obj'), 'w') as f:
        f.write(f'mtllib {name}.mtl\n')
        for p in positions:
            f.write(f'v {p[0]:.7g} {p[1]:.7g} {p[2]:.7g}\n')
        for p in positions:
            d = [p[a] - centre[a] for a in range(3)]
            r = math.sqrt(d[0] ** 2 + d[1] ** 2 + d[2] ** 2) or 1.0
            u = 0.5 + math.atan2(d[2], d[0]) / (2 * math.pi)
            v = 0.5 + math.asin(max(-1.0, min(1.0, d[1] / r))) / math.pi
            f.write(f'vt {u:.6f} {v:.6f}\n')
        f.write('usemtl surface\n')
        for a, b, c in tris:
            f.write(f'f {a + 1}/{a + 1} {b + 1}/{b + 1} {c + 1}/{c + 1}\n')
    write_png(os.path.join(out, name + '.png'), size)
    print(f'{out}/{name}.obj: {len(positions)} vertices, {len(tris)} faces, '
          f'{name}.png {size}x{size}')


if __name__ == '__main__':
    main()
