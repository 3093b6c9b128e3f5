#!/usr/bin/env python3
"""Regenerates tests/fuzz/seeds/ from real files: the test meshes of
tests/data, the sample meshes of data/ and the shared development meshes
(cut to their first lines: small seeds fuzz faster), the fixture
container data/octahedron_sr3.mwv (container_fuzz; 258 vertices, 38
packets) and the lighter fixture data/tetrahedron_sr2.mwv of packet_fuzz and
decoder_order_fuzz (34 vertices, 22 packets: an execution rebuilds a decoder,
so a smaller mesh fuzzes several times faster). Packets are split out with
protoc. The seeds made from the octahedron for those two targets are kept
(prefix octahedron_sr3_): any bytes are valid inputs there.

The fixtures themselves, after a .mwv format change (a build of the new
format in build/):
  build/tools/meshwave/meshwave encode --precision 12 --base-refinement 3 \
    --precinct-size 8 --split-bytes 2 \
    tests/fuzz/data/tetrahedron_sr2.obj tests/fuzz/data/tetrahedron_sr2.mwv
(a tetrahedron subdivided twice by midpoints, each vertex i moved radially
by 15 % * sin(3.1 i + 0.7) so that the details are not zero), and
  build/tools/meshwave/meshwave subdivide tests/fuzz/data/octahedron.off \
    /tmp/oct3.ply --levels 3 --scheme midpoint
  build/tools/meshwave/meshwave encode --base-refinement 2 --precinct-size 16 \
    --split-bytes 2 /tmp/oct3.ply tests/fuzz/data/octahedron_sr3.mwv
(tiny precincts, so that both have split packets: 2 and 3 precincts in
the tetrahedron's subband 1, 3 and 8 in the octahedron's subbands 1 and 2)

The asset targets (gltf_asset_fuzz, obj_asset_fuzz, image_decoder_fuzz)
get small documents written here (glTF JSON and buffers, OBJ + MTL, PNGs of
every layout), the project's textured samples (data/textured) and the
shared textured files (cut), and the JPEG and WebP files of
tests/fuzz/data/images/, which are checked in because Python's standard
library writes neither format: a 24 x 16 RGBA gradient through TurboJPEG's
tjCompress2 at quality 75 (4:2:0; 4:4:4 progressive; grey; from CMYK) and
libwebp's WebPEncodeRGBA / WebPEncodeRGB at quality 60 and
WebPEncodeLosslessRGBA.

Usage: python3 tests/fuzz/make_seeds.py [SHARED_MESHES_DIR]
"""
import hashlib
import json
import os
import random
import re
import shutil
import struct
import subprocess
import sys
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
SHARED = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "..", "shared", "data", "meshes")
SEEDS = os.path.join(HERE, "seeds")


def put(target, name, data):
    d = os.path.join(SEEDS, target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data)


def head_lines(path, lines):
    with open(path, "rb") as f:
        return b"".join(f.readline() for _ in range(lines))


def mesh_seeds():
    for sub in ("wellformed", "malformed"):
        d = os.path.join(ROOT, "tests", "data", sub)
        for name in sorted(os.listdir(d)):
            ext = name.rsplit(".", 1)[-1]
            put(ext + "_reader_fuzz", sub + "_" + name, open(os.path.join(d, name), "rb").read())
    put("off_reader_fuzz", "sample_elephant_head.off", head_lines(os.path.join(ROOT, "data", "elephant.off"), 60))
    for name in sorted(os.listdir(SHARED)):
        ext = name.rsplit(".", 1)[-1]
        if ext not in ("ply", "obj", "off"):
            continue
        path = os.path.join(SHARED, name)
        if ext == "ply":
            with open(path, "rb") as f:
                data = f.read(4096)
            put("ply_reader_fuzz", "shared_" + name, data)  # header and first elements
        else:
            put(ext + "_reader_fuzz", "shared_" + name, head_lines(path, 80))


def split_packets(data):
    """The payloads of a container, by packet id."""
    n = struct.unpack("<I", data[4:8])[0]
    header = data[8:8 + n]
    text = subprocess.run(["protoc", "--decode=meshwave.proto.StreamHeader", "-I" + os.path.join(ROOT, "proto"),
                           "stream.proto"], input=header, capture_output=True, check=True).stdout.decode()
    lengths = [int(x) for x in re.findall(r"^\s+length: (\d+)$", text, re.M)]
    payloads, pos = [], 8 + n
    for length in lengths:
        payloads.append(data[pos:pos + length])
        pos += length
    assert pos == len(data), (pos, len(data))
    return payloads


def decoder_seeds(payloads, prefix):
    """packet_fuzz and decoder_order_fuzz inputs for a fixture's packets."""
    for i, p in enumerate(payloads):
        if i % 3 == 0 or i == len(payloads) - 1:
            put("packet_fuzz", prefix + "packet%02d" % i, bytes([i]) + p)
    count = len(payloads)
    put("decoder_order_fuzz", prefix + "canonical", bytes(range(count)))
    put("decoder_order_fuzz", prefix + "reversed", bytes(reversed(range(count))))
    rng = random.Random(7)
    order = list(range(count))
    rng.shuffle(order)
    put("decoder_order_fuzz", prefix + "shuffled_twice", bytes(order + order))
    put("decoder_order_fuzz", prefix + "damaged", bytes([0x80, 0, 0x81, 1, 2, 0x83, 3, count + 1]))


def container_seeds():
    path = os.path.join(HERE, "data", "octahedron_sr3.mwv")
    data = open(path, "rb").read()
    put("container_fuzz", "octahedron_sr3.mwv", data)
    for cut in (0, 4, 8, 100, 700, 900, len(data) - 1):
        put("container_fuzz", "octahedron_sr3_cut%d.mwv" % cut, data[:cut])
    decoder_seeds(split_packets(data), "octahedron_sr3_")
    tiny = open(os.path.join(HERE, "data", "tetrahedron_sr2.mwv"), "rb").read()
    put("container_fuzz", "tetrahedron_sr2.mwv", tiny)
    decoder_seeds(split_packets(tiny), "")
    return hashlib.sha256(data).hexdigest()[:12]


def http_seeds(mesh_id):
    targets = [
        "/healthz", "/metrics", "/v1/meshes", "/v1/meshes?limit=10&offset=0",
        "/v1/meshes/%s" % mesh_id, "/v1/meshes/%s/header" % mesh_id,
        "/v1/meshes/%s/stream?order=rd&budget=800" % mesh_id,
        "/v1/meshes/%s/stream?order=quality&budget=300&from=3&max_level=2" % mesh_id,
        "/v1/meshes/%s/stream?order=resolution" % mesh_id,
        "/v1/meshes/%s/packets/7" % mesh_id, "/v1/meshes/%s/container" % mesh_id,
        "/v1/meshes/%2e%2e/container", "/v1/meshes/../x", "/v1/meshes/%s%%2fheader" % mesh_id,
    ]
    for i, t in enumerate(targets):
        put("http_request_fuzz", "get%02d" % i,
            ("GET %s HTTP/1.1\r\nHost: localhost\r\n\r\n" % t).encode())
    c = "/v1/meshes/%s/container" % mesh_id
    put("http_request_fuzz", "range", ("GET %s HTTP/1.1\r\nHost: x\r\nRange: bytes=10-99\r\n\r\n" % c).encode())
    put("http_request_fuzz", "range_suffix", ("GET %s HTTP/1.1\r\nRange: bytes=-5\r\n\r\n" % c).encode())
    put("http_request_fuzz", "etag", ("HEAD %s HTTP/1.1\r\nIf-None-Match: W/\"x\", *\r\n\r\n" % c).encode())
    put("http_request_fuzz", "protobuf", ("GET /v1/meshes/%s HTTP/1.1\r\nAccept: application/x-protobuf\r\n\r\n"
                                          % mesh_id).encode())
    put("http_request_fuzz", "post", b"POST /v1/meshes?name=a HTTP/1.1\r\nAuthorization: Bearer x\r\n"
                                     b"Content-Length: 3\r\n\r\nply")
    put("http_request_fuzz", "stream_region", ("GET /v1/meshes/%s/stream?region=0.1,0,0,0.5&held=Bw&budget=900 HTTP/1.1\r\n\r\n"
                                               % mesh_id).encode())
    put("http_request_fuzz", "stream_view", ("GET /v1/meshes/%s/stream?view=0,0,3,0,0,-1,45,800,600&screen_error=2 HTTP/1.1\r\n\r\n"
                                             % mesh_id).encode())
    put("http_request_fuzz", "chunked", ("GET /v1/meshes HTTP/1.1\r\nTransfer-Encoding: chunked\r\n\r\n"
                                         "3\r\nabc\r\n0\r\n\r\n").encode())


def varint(n):
    """LEB128, as protobuf writes it."""
    out = b""
    while True:
        low, n = n & 0x7F, n >> 7
        if not n:
            return out + bytes([low])
        out += bytes([low | 0x80])


def protobuf_field(number, wire_type, payload):
    """One protobuf field: varint key, then a length for wire type 2."""
    key = varint(number << 3 | wire_type)
    if wire_type == 2:
        return key + varint(len(payload)) + payload
    return key + varint(payload)


def header_seeds():
    """StreamHeader bytes for stream_header_fuzz: the fixtures' headers (with
    and without `present`) and records protobuf treats specially."""
    f = protobuf_field
    for name in ("octahedron_sr3", "tetrahedron_sr2"):
        data = open(os.path.join(HERE, "data", name + ".mwv"), "rb").read()
        (length,) = struct.unpack("<I", data[4:8])
        header = data[8:8 + length]
        put("stream_header_fuzz", name + "_header", header)
        put("stream_header_fuzz", name + "_header_cut", header[:length // 2])
    put("stream_header_fuzz", "unknown_and_group",
        f(99, 0, 5) + f(100, 2, b"xy") + bytes([0x9b, 0x06]) + f(1, 0, 4) + bytes([0x9c, 0x06]))
    put("stream_header_fuzz", "unpacked_and_merged",
        f(14, 0, 3) + f(14, 0, 1) + f(7, 2, f(4, 0, 2)) + f(7, 2, f(5, 2, f(1, 0, 9))))
    put("stream_header_fuzz", "utf8_name", f(2, 2, "caf\u00e9".encode()))
    put("stream_header_fuzz", "tetrahedron_sr2_header_texture",
        tetrahedron_texture_header(f, "image/png".encode()))
    put("stream_header_fuzz", "texture_mime_not_utf8",
        tetrahedron_texture_header(f, b"image/\xff"))


def tetrahedron_texture_header(f, mime):
    """The tetrahedron fixture's header as version 9 with a texture field
    (format section 2.4): a 2-cell atlas of 8-texel cells over its 4 base
    faces, one rotated face, the material's scalars, a PNG base colour map
    of two levels (8 x 4, 16 x 8) naming packets 22 and 23."""
    data = open(os.path.join(HERE, "data", "tetrahedron_sr2.mwv"), "rb").read()
    (length,) = struct.unpack("<I", data[4:8])
    floats = lambda *v: struct.pack("<%df" % len(v), *v)
    level = lambda packet, w, h: f(1, 0, packet) + f(2, 0, w) + f(3, 0, h)
    texture_map = (f(1, 0, 0) + f(2, 2, mime) + f(3, 2, level(22, 8, 4)) +
                   f(3, 2, level(23, 16, 8)))
    texture = (f(1, 0, 8) + f(2, 0, 0) + f(3, 0, 2) +
               f(4, 2, b"".join(varint(v) for v in (0, 3, 7, 11))) +
               bytes([0x2d]) + floats(1.0) + bytes([0x35]) + floats(0.5) +
               f(7, 2, floats(0.0, 0.1, 0.2)) + bytes([0x45]) + floats(1.0) +
               bytes([0x4d]) + floats(1.0) + f(11, 0, 1) + f(12, 2, texture_map) +
               bytes([0x6d]) + floats(1.0))
    return data[8:8 + length] + f(1, 0, 9) + f(16, 2, texture)


def ws_seeds():
    """ClientMessage frames of proto/websocket.proto: start, refine, resume."""
    f = protobuf_field
    mesh = b"0123456789ab"
    start = f(1, 2, mesh) + f(2, 2, b"rd") + f(3, 0, 2) + f(4, 0, 65536) + f(5, 0, 100000)
    put("ws_message_fuzz", "start_rd_budget_rate", f(1, 2, start))
    put("ws_message_fuzz", "start_header_only", f(1, 2, f(1, 2, mesh) + f(6, 0, 1)))
    put("ws_message_fuzz", "refine_4096", f(2, 2, f(1, 0, 4096)))
    resume = f(1, 2, mesh) + f(2, 2, b"quality") + f(4, 0, 5) + f(5, 0, 65536) + f(6, 0, 0)
    put("ws_message_fuzz", "resume_quality_cursor5", f(3, 2, resume))
    put("ws_message_fuzz", "start_region", f(1, 2, f(1, 2, mesh) + f(4, 0, 9000) + f(7, 2, b"0.1,0.2,0,0.5")))
    put("ws_message_fuzz", "refine_view", f(2, 2, f(1, 0, 4096) + f(3, 2, b"0,0,3,0,0,-1,45,800,600")))
    put("ws_message_fuzz", "refine_order", f(2, 2, f(1, 0, 4096) + f(5, 2, b"rd")))
    put("ws_message_fuzz", "resume_held_region", f(3, 2, f(1, 2, mesh) + f(7, 2, b"Bw") + f(8, 2, b"1,1,1,2")))


def client_seeds():
    """The client's parsers: a /stream body (a container) for
    stream_splitter_fuzz, a server's answers for ws_server_message_fuzz,
    a saved state (sidecar and container) for local_state_fuzz."""
    f = protobuf_field
    tiny = open(os.path.join(HERE, "data", "tetrahedron_sr2.mwv"), "rb").read()
    for seed, cut in ((0, len(tiny)), (7, len(tiny)), (200, 300), (3, 12)):
        put("stream_splitter_fuzz", "tetrahedron_sr2_%d_%d" % (seed, cut), bytes([seed]) + tiny[:cut])
    put("stream_splitter_fuzz", "header_over_limit", bytes([1]) + b"MWV1" + struct.pack("<I", 1 << 30) + b"x" * 40)

    def framed(flags, messages):
        return bytes([flags]) + b"".join(struct.pack("<H", len(m)) + m for m in messages)
    n = struct.unpack("<I", tiny[4:8])[0]
    header = tiny[8:8 + n]
    payloads = split_packets(tiny)
    selection = f(1, 0, 0) + f(2, 0, 3) + f(3, 0, len(payloads)) + f(4, 0, 8 + n + sum(map(len, payloads[:3])))
    packets = [f(3, 2, f(1, 0, i) + f(2, 0, i) + f(3, 2, payloads[i])) for i in range(3)]
    done = f(4, 2, f(1, 0, 3))
    # A start's answer (whole, and with a header cut short: the reader hands
    # it on, the decoder is not its business), a resume's, a refusal, text.
    put("ws_server_message_fuzz", "start", framed(1, [f(1, 2, f(1, 2, header) + f(2, 2, selection))] + packets + [done]))
    put("ws_server_message_fuzz", "start_small_header",
        framed(1, [f(1, 2, f(1, 2, header[:200]) + f(2, 2, selection))] + packets + [done]))
    resumed = f(1, 0, 1) + f(2, 0, 3) + f(3, 0, len(payloads)) + f(4, 0, 100)
    put("ws_server_message_fuzz", "resume", framed(0, [f(2, 2, resumed)] + packets[1:] + [done]))
    put("ws_server_message_fuzz", "error", framed(0, [f(5, 2, f(1, 0, 2) + f(2, 2, b"no such mesh"))]))
    put("ws_server_message_fuzz", "text_frame", framed(2, [f(4, 2, f(1, 0, 3))]))

    def state(url, order, max_level, cursor, budget, container):
        meta = f(1, 0, 1) + f(2, 2, url) + f(3, 2, order) + f(4, 0, max_level & 0xFFFFFFFFFFFFFFFF) \
            + f(5, 0, cursor) + f(6, 0, budget)
        return struct.pack("<H", len(meta)) + meta + container
    count = len(payloads)
    put("local_state_fuzz", "http_quality_all", state(b"http://127.0.0.1:8080/v1/meshes/0123456789ab", b"quality", -1, count, 5000, tiny))
    put("local_state_fuzz", "ws_rd_level1", state(b"ws://localhost:9/v1/meshes/abcdefabcdef", b"rd", 1, count, 9000, tiny))
    units_meta = f(1, 0, 1) + f(2, 2, b"http://127.0.0.1:8080/v1/meshes/0123456789ab") + f(3, 2, b"quality") \
        + f(4, 0, 0xFFFFFFFFFFFFFFFF) + f(6, 0, 4000) + f(7, 0, 1) + f(8, 2, varint(3) + varint(1) + varint(2) + b"xy") \
        + f(9, 2, b"Bw") + f(10, 2, b"sphere:0,0,0,1")
    put("local_state_fuzz", "units_state", struct.pack("<H", len(units_meta)) + units_meta + tiny)
    put("local_state_fuzz", "cursor_mismatch", state(b"https://h/v1/meshes/0123456789ab", b"resolution", 2, 3, 1, tiny))

def region_seeds():
    """region_fuzz: byte 0 picks the parser (0 sphere, 1 view, 2 screen
    error), the rest is the text a client sends."""
    put("region_fuzz", "sphere", b"\x00" + b"1.5,-2,0.3,0.25")
    put("region_fuzz", "sphere_nan", b"\x00" + b"1,2,nan,1")
    put("region_fuzz", "view", b"\x01" + b"0,0,5,0,0,-1,45,1920,1080")
    put("region_fuzz", "view_zero_direction", b"\x01" + b"0,0,5,0,0,0,45,640,480")
    put("region_fuzz", "screen_error", b"\x02" + b"0.75")


def stream_units_seeds():
    """stream_units_fuzz over tetrahedron_sr2.mwv: byte 0 even, a held
    bitmap's text; odd, a unit-records body (packet id, 0 or 1 + part,
    length: varints, then the payload)."""
    put("stream_units_fuzz", "held_nothing", b"\x00")
    put("stream_units_fuzz", "held_first_units", b"\x00" + b"Bw")
    put("stream_units_fuzz", "held_garbage", b"\x02" + b"a+b=")
    def record(pid, part, payload):
        return varint(pid) + varint(part) + varint(len(payload)) + payload
    put("stream_units_fuzz", "records", b"\x05" + record(0, 0, b"abc") + record(7, 2, b"xy") + record(3, 1, b""))
    put("stream_units_fuzz", "record_cut", b"\x01" + record(1, 0, b"abcdef")[:-2])


def png(width, height, color_type, depth, samples, interlaced=False, palette=b"", trns=b""):
    """A PNG of any layout: `samples` row-major, channel values below 2^depth."""
    channels = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}[color_type]

    def scanlines(x0, y0, dx, dy):
        out = b""
        for y in range(y0, height, dy):
            row, bits, filled = bytearray([0]), 0, 0
            for x in range(x0, width, dx):
                for c in range(channels):
                    v = samples[(y * width + x) * channels + c]
                    if depth == 16:
                        row += struct.pack(">H", v)
                    elif depth == 8:
                        row.append(v)
                    else:
                        bits, filled = (bits << depth) | v, filled + depth
                        if filled == 8:
                            row.append(bits)
                            bits, filled = 0, 0
            if filled:
                row.append((bits << (8 - filled)) & 0xFF)
            out += bytes(row)
        return out

    if interlaced:
        passes = [(0, 0, 8, 8), (4, 0, 8, 8), (0, 4, 4, 8), (2, 0, 4, 4), (0, 2, 2, 4),
                  (1, 0, 2, 2), (0, 1, 1, 2)]
        raw = b"".join(scanlines(*p) for p in passes if p[0] < width and p[1] < height)
    else:
        raw = scanlines(0, 0, 1, 1)

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    out = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, depth, color_type,
                                                              0, 0, int(interlaced)))
    if palette:
        out += chunk(b"PLTE", palette)
    if trns:
        out += chunk(b"tRNS", trns)
    return out + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")


def image_seeds():
    w, h = 10, 7
    grad = [(x * 25 + y * 3 + c * 40) % 256 for y in range(h) for x in range(w) for c in range(4)]
    put("image_decoder_fuzz", "rgba.png", png(w, h, 6, 8, grad))
    put("image_decoder_fuzz", "rgb_interlaced.png",
        png(w, h, 2, 8, [v for i, v in enumerate(grad) if i % 4 != 3], interlaced=True))
    put("image_decoder_fuzz", "grey16.png", png(w, h, 0, 16, [v * 257 for v in grad[::4]]))
    put("image_decoder_fuzz", "grey1.png", png(w, h, 0, 1, [v & 1 for v in grad[::4]]))
    put("image_decoder_fuzz", "grey_alpha.png", png(w, h, 4, 8, grad[: w * h * 2]))
    put("image_decoder_fuzz", "palette4_trns.png",
        png(w, h, 3, 4, [v % 3 for v in grad[::4]], palette=bytes([255, 0, 0, 0, 255, 0, 0, 0, 255]),
            trns=b"\x80"))
    put("image_decoder_fuzz", "rgba_truncated.png", png(w, h, 6, 8, grad)[:-30])
    put("image_decoder_fuzz", "die.png", open(os.path.join(ROOT, "data", "textured", "die.png"), "rb").read())
    images = os.path.join(HERE, "data", "images")
    for name in sorted(os.listdir(images)):
        put("image_decoder_fuzz", name, open(os.path.join(images, name), "rb").read())


def glb(doc, bin_chunk):
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    bin_chunk += b"\0" * (-len(bin_chunk) % 4)
    out = struct.pack("<I4s", len(text), b"JSON") + text
    if bin_chunk:
        out += struct.pack("<I4s", len(bin_chunk), b"BIN\0") + bin_chunk
    return struct.pack("<4sII", b"glTF", 2, 12 + len(out)) + out


def gltf_document(image_view=None):
    """A quad in two triangles (positions, UVs, colours, uint16 indices)
    under a two-node tree, a material with a texture; and its buffer."""
    positions = struct.pack("<12f", 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0)
    uvs = struct.pack("<8f", 0, 1, 1, 1, 1, 0, 0, 0)
    colours = bytes([255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 128])
    indices = struct.pack("<6H", 0, 1, 2, 0, 2, 3) + b"\0\0"
    blob = positions + uvs + colours + indices
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
             {"buffer": 0, "byteOffset": 48, "byteLength": 32},
             {"buffer": 0, "byteOffset": 80, "byteLength": 16},
             {"buffer": 0, "byteOffset": 96, "byteLength": 12}]
    doc = {
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_texture_transform"],
        "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"rotation": [0, 0, 0.7071068, 0.7071068], "scale": [2, 2, 2], "children": [1]},
                  {"translation": [0, 0, 1], "mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1, "COLOR_0": 2},
                                    "indices": 3, "material": 0}]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
             "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 2, "componentType": 5121, "normalized": True, "count": 4, "type": "VEC4"},
            {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}],
        "bufferViews": views,
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "extensions": {
            "KHR_texture_transform": {"offset": [0.5, 0], "scale": [2, 2]}}}}}],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{"wrapS": 33071, "wrapT": 33648}],
        "images": [{"uri": "a.png"}],
    }
    if image_view is not None:
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(image_view)})
        blob += image_view
        doc["images"] = [{"bufferView": 4, "mimeType": "image/png"}]
    doc["buffers"] = [{"byteLength": len(blob)}]
    return doc, blob


def asset_seeds():
    sep = b"\n--file--\n"
    tiny = png(4, 4, 6, 8, [(i * 37) % 256 for i in range(64)])
    doc, blob = gltf_document(tiny)
    put("gltf_asset_fuzz", "quad_textured.glb", b"\x00" + glb(doc, blob))
    strip = dict(doc)
    strip["meshes"] = [{"primitives": [{"attributes": {"POSITION": 0}, "mode": 5},
                                       {"attributes": {"POSITION": 0}, "indices": 3, "mode": 6}]}]
    put("gltf_asset_fuzz", "strip_fan.glb", b"\x00" + glb(strip, blob))
    sparse = json.loads(json.dumps(doc))
    sparse["accessors"][0]["sparse"] = {"count": 1, "indices": {"bufferView": 3, "componentType": 5123},
                                        "values": {"bufferView": 0}}
    put("gltf_asset_fuzz", "sparse.glb", b"\x00" + glb(sparse, blob))
    doc, blob = gltf_document()
    doc["buffers"][0]["uri"] = "m.bin"
    put("gltf_asset_fuzz", "quad.gltf", b"\x01" + json.dumps(doc).encode() + sep + blob + sep + tiny)
    ring = open(os.path.join(ROOT, "data", "textured", "ring.glb"), "rb").read()
    put("gltf_asset_fuzz", "ring.glb", b"\x00" + ring)
    for name in ("ToyCar/ToyCar.gltf", "IridescenceAbalone/IridescenceAbalone.gltf"):
        path = os.path.join(SHARED, "..", "textured", name)
        if os.path.exists(path):  # their JSON only: the gate, tinygltf's parse
            put("gltf_asset_fuzz", "shared_" + os.path.basename(name), b"\x01" + open(path, "rb").read())

    mtl = (b"newmtl a\nKd 1 0.5 0.25\nd 0.5\nmap_Kd -s 2 2 1 -o 0.5 0 -clamp on t.png\n"
           b"map_Bump -bm 0.8 t.png\nPr 0.4\nnewmtl b\nTr 0.2\nKe 1 1 0\n")
    obj = (b"mtllib m.mtl\nv 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 1 1 0 0 0 1\nv 0 1 0\n"
           b"vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nusemtl a\nf 1/1/1 2/2/1 3/3/1 4/4/1\n"
           b"usemtl b\nf -4//1 -2//1 -1//1\nf 1 3 4\nl 1 2\n")
    put("obj_asset_fuzz", "quad", obj + sep + mtl + sep + tiny)
    die = os.path.join(ROOT, "data", "textured")
    put("obj_asset_fuzz", "die_head", head_lines(os.path.join(die, "die.obj"), 40) + sep +
        open(os.path.join(die, "die.mtl"), "rb").read() + sep + tiny)
    cow = os.path.join(SHARED, "..", "textured", "spot")
    if os.path.isdir(cow):
        put("obj_asset_fuzz", "shared_cow_head", head_lines(os.path.join(cow, "cow.obj"), 80) + sep +
            open(os.path.join(cow, "cow.mtl"), "rb").read())
    d = os.path.join(ROOT, "tests", "data", "wellformed")
    for name in sorted(os.listdir(d)):
        if name.endswith(".obj"):
            put("obj_asset_fuzz", "wellformed_" + name, open(os.path.join(d, name), "rb").read())
    image_seeds()


if __name__ == "__main__":
    if os.path.isdir(SEEDS):
        shutil.rmtree(SEEDS)
    mesh_seeds()
    http_seeds(container_seeds())
    header_seeds()
    ws_seeds()
    client_seeds()
    region_seeds()
    stream_units_seeds()
    asset_seeds()
