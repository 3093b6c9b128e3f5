#!/usr/bin/env python3
"""The texture code's candidates on real baked atlases, and what the rendered
picture makes of resolution against quality.

For each mesh: `meshwave encode --texture-quality 100` bakes its base colour
into the remesh's atlas; the full-size level (WebP at quality 100, about
50 dB from the bake) is the source. Then:

  1. Codecs at equal bytes (luma PSNR of the atlas against the source):
     baseline JPEG (cjpeg -optimize, 4:2:0), progressive JPEG (cjpeg
     -progressive), lossy WebP (cwebp) and JPEG 2000 (opj_compress -I, the
     9/7 wavelet, at the WebP file's bytes), at QUALITIES.
  2. Resolution against quality, as seen: the complete stream's mesh drawn
     with the atlas as WebP at scale 1, 1/2, 1/4 and each quality,
     `meshwave render-compare` against the input (16 views, 1024 pixels, 2x2
     samples): bytes of the map and the picture's luma PSNR.

Writes OUT/texture_codec_table.tsv (part 1) and OUT/texture_render_table.tsv
(part 2).

Usage: bench/texture_codec_table.py [BUILD_DIR] [TEXTURED_DIR] [OUT_DIR]
  BUILD_DIR: a build with -DMESHWAVE_BENCH=ON (default build-bench)
  MESHES="spot/cow.obj IridescenceAbalone/IridescenceAbalone.gltf"
  QUALITIES="20 30 50 70 90"   FIDELITY_<name>: --fidelity for that mesh
Needs cjpeg/djpeg, cwebp/dwebp, opj_compress/opj_decompress
(bash deploy/install-deps.sh bench).
"""
import json
import math
import os
import shutil
import struct
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from texture_table import arguments, base_colour_only, run  # noqa: E402


def read_ppm(path):
    data = open(path, 'rb').read()
    fields, at = [], 0
    while len(fields) < 4:
        while data[at:at + 1].isspace():
            at += 1
        if data[at:at + 1] == b'#':
            at = data.index(b'\n', at)
            continue
        end = at
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[at:end])
        at = end
    return int(fields[1]), int(fields[2]), data[at + 1:]


def luma_psnr(a_path, b_path):
    w, h, a = read_ppm(a_path)
    _, _, b = read_ppm(b_path)
    total = 0.0
    for k in range(0, 3 * w * h, 3):
        d = (0.2126 * (a[k] - b[k]) + 0.7152 * (a[k + 1] - b[k + 1]) +
             0.0722 * (a[k + 2] - b[k + 2]))
        total += d * d
    return math.inf if total == 0 else 10 * math.log10(255 * 255 * w * h / total)


def glb_parts(path):
    data = open(path, 'rb').read()
    json_length, = struct.unpack('<I', data[12:16])
    doc = json.loads(data[20:20 + json_length])
    at = 20 + json_length
    bin_length, = struct.unpack('<I', data[at:at + 4])
    return doc, data[at + 8:at + 8 + bin_length]


def split_glb(glb, out_dir):
    """The decode as .gltf + .bin + its base colour image file; the image's path."""
    doc, blob = glb_parts(glb)
    image = doc['images'][0]
    view = doc['bufferViews'][image.pop('bufferView')]
    start = view.get('byteOffset', 0)
    suffix = image.pop('mimeType').split('/')[1]
    atlas = os.path.join(out_dir, 'atlas.' + suffix)
    open(atlas, 'wb').write(blob[start:start + view['byteLength']])
    open(os.path.join(out_dir, 'mesh.bin'), 'wb').write(blob)
    doc['buffers'] = [{'uri': 'mesh.bin', 'byteLength': len(blob)}]
    image['uri'] = os.path.basename(atlas)
    return doc, atlas


def main():
    args = arguments(__doc__)
    if args is None:
        return
    build, textured, out_dir = args
    for tool in ('cjpeg', 'djpeg', 'cwebp', 'dwebp', 'opj_compress', 'opj_decompress'):
        if shutil.which(tool) is None:
            sys.exit(f'{tool} is needed (bash deploy/install-deps.sh bench)')
    cli = os.path.join(build, 'tools', 'meshwave', 'meshwave')
    meshes = os.environ.get('MESHES',
                            'spot/cow.obj IridescenceAbalone/IridescenceAbalone.gltf').split()
    qualities = os.environ.get('QUALITIES', '20 30 50 70 90').split()
    os.makedirs(out_dir, exist_ok=True)
    codecs = open(os.path.join(out_dir, 'texture_codec_table.tsv'), 'w')
    codecs.write('mesh\tquality\tjpeg B\tjpeg dB\tprogressive B\tprogressive dB\twebp B\twebp dB\t'
                 'j2k B\tj2k dB\n')
    renders = open(os.path.join(out_dir, 'texture_render_table.tsv'), 'w')
    renders.write('mesh\tscale\tquality\twebp B\trendered dB\n')
    for rel in meshes:
        name = os.path.splitext(os.path.basename(rel))[0]
        work = os.path.join(out_dir, name)
        shutil.rmtree(work, ignore_errors=True)
        os.makedirs(work)
        asset = base_colour_only(os.path.dirname(os.path.join(textured, rel)),
                                 os.path.basename(rel), work)
        stream = os.path.join(work, 'q100.mwv')
        args = [cli, 'encode', '--texture-quality', '100', asset, stream]
        if os.environ.get(f'FIDELITY_{name}'):
            args += ['--fidelity', os.environ[f'FIDELITY_{name}']]
        run(args)
        run([cli, 'decode', stream, os.path.join(work, 'complete.glb')])
        doc, atlas = split_glb(os.path.join(work, 'complete.glb'), work)
        source = os.path.join(work, 'source.ppm')
        run(['dwebp', '-quiet', atlas, '-ppm', '-o', source])
        for q in qualities:
            row = [name, q]
            for kind, encode, decode in (
                    ('jpg', ['cjpeg', '-quality', q, '-optimize'], ['djpeg', '-ppm']),
                    ('prog.jpg', ['cjpeg', '-quality', q, '-progressive'], ['djpeg', '-ppm'])):
                coded = os.path.join(work, f'q{q}.{kind}')
                with open(coded, 'wb') as f:
                    f.write(run(encode + [source], text=False).stdout)
                with open(coded + '.ppm', 'wb') as f:
                    f.write(run(decode + [coded], text=False).stdout)
                row += [os.path.getsize(coded), f'{luma_psnr(source, coded + ".ppm"):.2f}']
            webp = os.path.join(work, f'q{q}.webp')
            run(['cwebp', '-quiet', '-q', q, source, '-o', webp])
            run(['dwebp', '-quiet', webp, '-ppm', '-o', webp + '.ppm'])
            row += [os.path.getsize(webp), f'{luma_psnr(source, webp + ".ppm"):.2f}']
            j2k = os.path.join(work, f'q{q}.j2k')
            ratio = os.path.getsize(source) / os.path.getsize(webp)  # raw : coded
            run(['opj_compress', '-I', '-i', source, '-o', j2k, '-r', f'{ratio:.3f}'])
            run(['opj_decompress', '-i', j2k, '-o', j2k + '.ppm'])
            row += [os.path.getsize(j2k), f'{luma_psnr(source, j2k + ".ppm"):.2f}']
            codecs.write('\t'.join(map(str, row)) + '\n')
            codecs.flush()
        variants = os.path.join(work, 'variants')
        os.makedirs(variants)
        listing = run([os.path.join(build, 'bench', 'texture_variants'), atlas, variants,
                       ','.join(qualities)]).stdout
        sizes, drawn = {}, []
        for line in listing.splitlines():
            path, size, _ = line.split('\t')
            if path.endswith('.webp'):
                mesh_file = os.path.join(work, 'with_' + os.path.basename(path) + '.gltf')
                doc['images'][0]['uri'] = os.path.relpath(path, work)
                json.dump(doc, open(mesh_file, 'w'))
                sizes[mesh_file] = (os.path.basename(path), int(size))
                drawn.append(mesh_file)
        scored = run([cli, 'render-compare', asset] + drawn).stdout
        for line in scored.splitlines():
            db, _, path = line.split('\t')
            variant, size = sizes[path]
            scale, q = variant[1:-5].split('_q')
            renders.write(f'{name}\t1/{scale}\t{q}\t{size}\t{db}\n')
            renders.flush()
    print(os.path.join(out_dir, 'texture_codec_table.tsv'))
    print(os.path.join(out_dir, 'texture_render_table.tsv'))


if __name__ == '__main__':
    main()
