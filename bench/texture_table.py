#!/usr/bin/env python3
"""Textured meshes against the anchors a user would pick instead, judged by
what the user sees: the rendered image.

For each mesh, every coder gets the same input: the asset with its base
colour map only (the measure draws base colour: other maps would be bytes
no picture shows). Every decode is drawn from the same cameras as the
input (`meshwave render-compare`: VIEWS cameras around it, SIZE pixels a
side, base colour without light) and scored by luma PSNR over the object's
pixels.

  (a) Draco + JPEG: draco_encoder -cl 10 at each qp in QPS and qt in QTS,
      decoded by draco_decoder, with the base colour re-encoded as JPEG at
      each quality in QUALITIES and at scale 1, 1/2 and 1/4
      (bench/texture_variants). Single-material meshes only: Draco's
      command-line decoder drops the material of each face.
  (b) gltfpack + WebP: gltfpack -cc (meshopt, its default quantisation);
      the bytes are the compressed .bin and the JSON, the picture is drawn
      from gltfpack's uncompressed output at the same quantisation (the
      compression is lossless), with the base colour as lossy WebP (libwebp)
      at the same qualities and scales.
  An anchor's bytes at a quality are its cheapest combination that reaches
  it (the lower envelope over all combinations).

  meshwave: `meshwave encode` with defaults (FIDELITY_<name> sets
  --fidelity, e.g. 0 for the glTF assets the remesher is slow on), decoded
  at budgets from 1 KB to the whole stream, and bisected to the smallest
  prefix that reaches each quality point.

Quality points: the better anchor's envelope spans [lo, hi] dB (its cheapest
and its best combination); the points are lo + (hi - lo) x 1/4, 1/2, 3/4, 1.

Writes OUT/texture_table.tsv (one row per mesh and point) and
OUT/<name>/curves.tsv (every combination and prefix measured).

Usage: bench/texture_table.py [BUILD_DIR] [TEXTURED_DIR] [OUT_DIR]
  BUILD_DIR: a build with -DMESHWAVE_BENCH=ON (default build-bench)
  TEXTURED_DIR: default ../shared/data/textured
  MESHES="spot/cow.obj IridescenceAbalone/IridescenceAbalone.gltf"
  QPS="8 10 12 14"  QTS="10 12"  QUALITIES=50,65,80,95  VIEWS=16  SIZE=1024
  ENCODE_ARGS="..."  more `meshwave encode` options (e.g. --texture-quality 30)
  REUSE_ANCHORS=1: take the anchors' rows from OUT/<name>/curves.tsv of an
  earlier run with the same settings instead of measuring them again
Needs draco_encoder, draco_decoder, gltfpack, jq (bash deploy/install-deps.sh bench).
"""
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile


def run(args, **kw):
    kw.setdefault('text', True)
    r = subprocess.run(args, capture_output=True, **kw)
    if r.returncode != 0:
        err = r.stderr if isinstance(r.stderr, str) else r.stderr.decode(errors='replace')
        sys.exit(f'texture_table: {" ".join(map(str, args))} failed:\n{err[-2000:]}')
    return r


class Scorer:
    """render-compare against one reference, many meshes per call."""

    def __init__(self, cli, reference, views, size):
        self.cli, self.reference, self.views, self.size = cli, reference, views, size

    def score(self, meshes):
        if not meshes:
            return {}
        r = run([self.cli, 'render-compare', '--views', str(self.views), '--size',
                 str(self.size), self.reference] + meshes)
        out = {}
        for line in r.stdout.splitlines():
            db, _, path = line.split('\t')
            out[path] = float(db)
        return out


def base_colour_only(src_dir, main, work):
    """A copy of the asset whose materials keep their base colour map only."""
    dst = os.path.join(work, 'input')
    shutil.copytree(src_dir, dst)
    for f in os.listdir(dst):
        os.chmod(os.path.join(dst, f), 0o644)
    path = os.path.join(dst, main)
    if main.endswith('.gltf'):
        doc = json.load(open(path))
        for m in doc.get('materials', []):
            for key in ('normalTexture', 'occlusionTexture', 'emissiveTexture', 'extensions'):
                m.pop(key, None)
            m.get('pbrMetallicRoughness', {}).pop('metallicRoughnessTexture', None)
        # Only the textures and images the base colours use (a packer keeps
        # unused images, and their bytes would count).
        used = [m['pbrMetallicRoughness']['baseColorTexture'] for m in doc.get('materials', [])
                if 'baseColorTexture' in m.get('pbrMetallicRoughness', {})]
        textures, images = [], []
        for ref in used:
            texture = dict(doc['textures'][ref['index']])
            image = doc['images'][texture['source']]
            if image not in images:
                images.append(image)
            texture['source'] = images.index(image)
            ref['index'] = len(textures)
            textures.append(texture)
        doc['textures'], doc['images'] = textures, images
        for key in ('textures', 'images'):
            if not doc[key]:
                del doc[key]
        json.dump(doc, open(path, 'w'))
    return path


def base_colour_images(asset):
    """The base colour image files of a .gltf or OBJ (+ MTL) asset."""
    folder = os.path.dirname(asset)
    if asset.endswith('.gltf'):
        doc = json.load(open(asset))
        out = []
        for m in doc.get('materials', []):
            t = m.get('pbrMetallicRoughness', {}).get('baseColorTexture')
            if t is not None:
                uri = doc['images'][doc['textures'][t['index']]['source']]['uri']
                out.append(os.path.join(folder, uri))
        return out
    if asset.endswith('.obj'):
        mtls = re.findall(r'^mtllib\s+(\S+)', open(asset).read(), re.M)
        out = []
        for mtl in mtls:
            out += [os.path.join(folder, m) for m in
                    re.findall(r'^\s*map_Kd\s+(\S+)', open(os.path.join(folder, mtl)).read(), re.M)]
        return out
    return []


def texture_variants(build, images, work):
    """{(scale, quality, kind): [(file, bytes)] per image}."""
    variants = {}
    for i, image in enumerate(images):
        d = os.path.join(work, f't{i}')
        os.makedirs(d, exist_ok=True)
        r = run([os.path.join(build, 'bench', 'texture_variants'), image, d, QUALITIES])
        for line in r.stdout.splitlines():
            path, size, _ = line.split('\t')
            m = re.search(r's(\d+)_q(\d+)\.(jpg|webp)$', path)
            variants.setdefault((int(m[1]), int(m[2]), m[3]), []).append((path, int(size)))
    return variants


def draco_anchor(asset, image, variants, scorer, work):
    rows = []
    for qp in QPS:
        for qt in QTS:
            stem = os.path.join(work, f'draco_qp{qp}_qt{qt}')
            run(['draco_encoder', '-i', asset, '-o', stem + '.drc', '-cl', '10', '-qp', str(qp),
                 '-qt', str(qt)])
            run(['draco_decoder', '-i', stem + '.drc', '-o', stem + '.obj'])
            geometry = os.path.getsize(stem + '.drc')
            body = open(stem + '.obj').read()
            meshes = {}
            for (scale, q, kind), files in variants.items():
                if kind != 'jpg':
                    continue
                tex, tex_bytes = files[0]
                name = f'{stem}_s{scale}_q{q}'
                # Relative: the readers refuse paths that leave the mesh's folder.
                open(name + '.mtl', 'w').write(f'newmtl m\nmap_Kd {os.path.relpath(tex, work)}\n')
                open(name + '.obj', 'w').write(
                    f'mtllib {os.path.basename(name)}.mtl\nusemtl m\n' + body)
                meshes[name + '.obj'] = (f'draco qp {qp} qt {qt} + jpeg 1/{scale} q{q}',
                                         geometry + tex_bytes)
            for path, db in scorer.score(list(meshes)).items():
                rows.append(('draco+jpeg', meshes[path][0], meshes[path][1], db))
    return rows


def gltfpack_anchor(asset, variants, scorer, work):
    packed = os.path.join(work, 'gltfpack_cc')
    os.makedirs(packed, exist_ok=True)
    run(['gltfpack', '-i', asset, '-o', os.path.join(packed, 'm.gltf'), '-cc'])
    geometry = (os.path.getsize(os.path.join(packed, 'm.gltf')) +
                os.path.getsize(os.path.join(packed, 'm.bin')))
    plain = work  # beside the texture variants: readers refuse paths out of the folder
    run(['gltfpack', '-i', asset, '-o', os.path.join(plain, 'gltfpack.gltf')])
    doc = json.load(open(os.path.join(plain, 'gltfpack.gltf')))
    originals = [os.path.normpath(os.path.join(os.path.dirname(asset), p))
                 for p in base_colour_images(asset)]
    meshes = {}
    for (scale, q, kind), files in variants.items():
        if kind != 'webp':
            continue
        d = json.loads(json.dumps(doc))
        tex_bytes = 0
        for image in d.get('images', []):
            src = os.path.normpath(os.path.join(os.path.dirname(asset), image['uri']))
            if src in originals:
                path, size = files[originals.index(src)]
                image['uri'] = os.path.relpath(path, plain)
                tex_bytes += size
        name = os.path.join(plain, f'webp_s{scale}_q{q}.gltf')
        json.dump(d, open(name, 'w'))
        meshes[name] = (f'gltfpack -cc + webp 1/{scale} q{q}', geometry + tex_bytes)
    return [('gltfpack+webp', meshes[p][0], meshes[p][1], db)
            for p, db in scorer.score(list(meshes)).items()]


def envelope(rows, quality):
    """The cheapest row reaching `quality` dB, or None."""
    best = None
    for row in rows:
        if row[3] >= quality - 1e-9 and (best is None or row[2] < best[2]):
            best = row
    return best


class Meshwave:
    def __init__(self, cli, asset, scorer, work, fidelity):
        self.cli, self.scorer, self.work = cli, scorer, work
        self.stream = os.path.join(work, 'meshwave.mwv')
        args = [cli, 'encode', asset, self.stream] + os.environ.get('ENCODE_ARGS', '').split()
        if fidelity is not None:
            args += ['--fidelity', fidelity]
        run(args)
        self.total = os.path.getsize(self.stream)
        self.cache = {}

    def at(self, budget):
        """(bytes, dB, vertices, texture) of the prefix of `budget` bytes."""
        budget = min(budget, self.total)
        if budget in self.cache:
            return self.cache[budget]
        out = os.path.join(self.work, f'prefix_{budget}.glb')
        r = subprocess.run([self.cli, 'decode', '--budget', str(budget), self.stream, out],
                           capture_output=True, text=True)
        if r.returncode != 0:  # below the header: nothing to draw
            self.cache[budget] = (budget, -math.inf, 0, '-')
            return self.cache[budget]
        text = r.stdout + r.stderr
        vertices = re.search(r'(\d+) vertices', text)
        texture = re.search(r'base colour (\d+ x \d+)', text)
        db = self.scorer.score([out])[out]
        os.remove(out)
        self.cache[budget] = (budget, db, int(vertices[1]) if vertices else 0,
                              texture[1] if texture else '-')
        return self.cache[budget]

    def smallest_reaching(self, quality):
        """The smallest measured budget whose prefix reaches `quality`, bisected."""
        budgets = sorted(self.cache)
        hi = next((b for b in budgets if self.cache[b][1] >= quality), None)
        if hi is None:
            return None
        below = [b for b in budgets if b < hi]
        lo = below[-1] if below else 0
        while hi - lo > max(64, hi // 200):
            mid = (lo + hi) // 2
            if self.at(mid)[1] >= quality:
                hi = mid
            else:
                lo = mid
        return self.at(hi)


def arguments(usage):
    """BUILD_DIR, TEXTURED_DIR and OUT_DIR from the command line, with their
    defaults; None after printing `usage` for -h."""
    if len(sys.argv) > 1 and sys.argv[1] in ('-h', '--help'):
        print(usage)
        return None
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    build = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, 'build-bench'))
    textured = os.path.abspath(sys.argv[2] if len(sys.argv) > 2 else
                               os.path.join(root, '..', 'shared', 'data', 'textured'))
    out_dir = os.path.abspath(sys.argv[3] if len(sys.argv) > 3 else tempfile.mkdtemp())
    return build, textured, out_dir


def main():
    args = arguments(__doc__)
    if args is None:
        return
    build, textured, out_dir = args
    cli = os.path.join(build, 'tools', 'meshwave', 'meshwave')
    for tool in ('draco_encoder', 'draco_decoder', 'gltfpack'):
        if shutil.which(tool) is None:
            sys.exit(f'{tool} is needed (bash deploy/install-deps.sh bench)')
    for f in (cli, os.path.join(build, 'bench', 'texture_variants')):
        if not os.path.exists(f):
            sys.exit(f'texture_table: no {f}: build with -DMESHWAVE_BENCH=ON '
                     '(ninja meshwave texture_variants)')
    os.makedirs(out_dir, exist_ok=True)
    table = open(os.path.join(out_dir, 'texture_table.tsv'), 'w')
    table.write('mesh\tpoint\ttarget dB\tanchor\tanchor bytes\tmeshwave bytes\tratio\t'
                'meshwave dB\tvertices\ttexture\n')
    for rel in MESHES:
        name = os.path.splitext(os.path.basename(rel))[0]
        src = os.path.join(textured, rel)
        if not os.path.exists(src):
            sys.exit(f'texture_table: no {src}')
        work = os.path.join(out_dir, name)
        curves_path = os.path.join(work, 'curves.tsv')
        earlier = []
        if os.environ.get('REUSE_ANCHORS') and os.path.exists(curves_path):
            for line in open(curves_path).read().splitlines()[1:]:
                coder, setting, size, db = line.split('\t')
                if coder != 'meshwave':
                    earlier.append((coder, setting, int(size), float(db)))
        shutil.rmtree(work, ignore_errors=True)
        os.makedirs(work)
        asset = base_colour_only(os.path.dirname(src), os.path.basename(src), work)
        work = os.path.join(work, 'anchors')  # every decode and texture variant
        os.makedirs(work)
        scorer = Scorer(cli, asset, VIEWS, SIZE)
        images = base_colour_images(asset)
        print(f'{name}: base colour {", ".join(os.path.basename(i) for i in images)}',
              file=sys.stderr)
        if earlier:
            rows = earlier
        else:
            variants = texture_variants(build, images, work)
            rows = gltfpack_anchor(asset, variants, scorer, work)
            if len(images) == 1:
                rows += draco_anchor(asset, images[0], variants, scorer, work)
        print(f'{name}: {len(rows)} anchor combinations measured', file=sys.stderr)
        mw = Meshwave(cli, asset, scorer, work, os.environ.get(f'FIDELITY_{name}'))
        budget = 1024
        while budget < mw.total:
            mw.at(budget)
            budget = int(budget * 1.5)
        mw.at(mw.total)
        lo = min(rows, key=lambda r: r[2])[3]  # the cheapest combination's
        hi = max(r[3] for r in rows)
        with open(curves_path, 'w') as curves:
            curves.write('coder\tsetting\tbytes\tdB\n')
            for r in sorted(rows, key=lambda r: (r[0], r[2])):
                curves.write(f'{r[0]}\t{r[1]}\t{r[2]}\t{r[3]:.3f}\n')
            for b in sorted(mw.cache):
                _, db, v, tex = mw.cache[b]
                curves.write(f'meshwave\t{v} vertices, texture {tex}\t{b}\t{db:.3f}\n')
        for k, share in enumerate((0.25, 0.5, 0.75, 1.0)):
            target = lo + (hi - lo) * share
            anchor = envelope(rows, target)
            mine = mw.smallest_reaching(target)
            if mine is None:
                best = max(mw.cache.values(), key=lambda c: c[1])
                line = (f'{name}\t{k + 1}\t{target:.2f}\t{anchor[0]}: {anchor[1]}\t{anchor[2]}\t'
                        f'not reached (complete stream {mw.total} B: {best[1]:.2f} dB)\t-\t'
                        f'{best[1]:.2f}\t{best[2]}\t{best[3]}\n')
            else:
                line = (f'{name}\t{k + 1}\t{target:.2f}\t{anchor[0]}: {anchor[1]}\t{anchor[2]}\t'
                        f'{mine[0]}\t{mine[0] / anchor[2]:.2f}\t{mine[1]:.2f}\t{mine[2]}\t'
                        f'{mine[3]}\n')
            table.write(line)
            table.flush()
            sys.stderr.write(line)
    print(os.path.join(out_dir, 'texture_table.tsv'))


MESHES = os.environ.get('MESHES', 'spot/cow.obj IridescenceAbalone/IridescenceAbalone.gltf').split()
QPS = os.environ.get('QPS', '8 10 12 14').split()
QTS = os.environ.get('QTS', '10 12').split()
QUALITIES = os.environ.get('QUALITIES', '50,65,80,95')
VIEWS = int(os.environ.get('VIEWS', '16'))
SIZE = int(os.environ.get('SIZE', '1024'))

if __name__ == '__main__':
    main()
