#!/usr/bin/env python3
"""PSNR in dB between two pictures of `meshwave render` (8-bit RGB or RGBA
PNG, same size), over the pixels that are not white background in both:
how close a decoded mesh's picture is to the original's.

Usage: bench/render_psnr.py REFERENCE.png PICTURE.png
Standard library only (zlib): PNG filters 0-4, no interlacing.
"""
import math
import struct
import sys
import zlib


def read_png(path):
    data = open(path, 'rb').read()
    if data[:8] != b'\x89PNG\r\n\x1a\n':
        sys.exit(f'{path}: not a PNG')
    pos, idat, width, height, bpp = 8, b'', 0, 0, 0
    while pos < len(data):
        length, = struct.unpack('>I', data[pos:pos + 4])
        kind, chunk = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b'IHDR':
            width, height, depth, colour = struct.unpack('>IIBB', chunk[:10])
            if depth != 8 or colour not in (2, 6) or chunk[12] != 0:
                sys.exit(f'{path}: only 8-bit RGB or RGBA, not interlaced')
            bpp = 3 if colour == 2 else 4
        elif kind == b'IDAT':
            idat += chunk
    raw, stride = zlib.decompress(idat), width * bpp
    out, prev, pos = bytearray(), bytearray(stride), 0
    for _ in range(height):
        kind, row = raw[pos], bytearray(raw[pos + 1:pos + 1 + stride])
        pos += 1 + stride
        for x in range(stride):
            a = row[x - bpp] if x >= bpp else 0
            b = prev[x]
            c = prev[x - bpp] if x >= bpp else 0
            if kind == 1:
                row[x] = (row[x] + a) & 255
            elif kind == 2:
                row[x] = (row[x] + b) & 255
            elif kind == 3:
                row[x] = (row[x] + (a + b) // 2) & 255
            elif kind == 4:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                row[x] = (row[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        out += row
        prev = row
    return width, height, bpp, out


def main():
    if len(sys.argv) != 3 or sys.argv[1] in ('-h', '--help'):
        print(__doc__)
        sys.exit(0 if len(sys.argv) > 1 and sys.argv[1] in ('-h', '--help') else 2)
    w, h, bpp_a, a = read_png(sys.argv[1])
    w2, h2, bpp_b, b = read_png(sys.argv[2])
    if (w, h) != (w2, h2):
        sys.exit(f'the pictures differ in size: {w}x{h} and {w2}x{h2}')
    squared, pixels = 0, 0
    for i in range(w * h):
        pa, pb = a[i * bpp_a:i * bpp_a + 3], b[i * bpp_b:i * bpp_b + 3]
        if sum(pa) >= 3 * 250 and sum(pb) >= 3 * 250:
            continue  # background in both
        pixels += 1
        squared += sum((x - y) ** 2 for x, y in zip(pa, pb))
    mse = squared / (3 * max(pixels, 1))
    print('inf' if mse == 0 else f'{10 * math.log10(255 * 255 / mse):.2f}')


main()
