#!/usr/bin/env python3
"""A meshwave client written from docs/API.md, docs/FORMAT.md and the
protos alone, in Python: it interoperates with meshwave-server over HTTP
and WebSocket, byte for byte.

It starts its own meshwave-server on 127.0.0.1 (ingesting one sample mesh
into a temporary catalog) and checks:
- HTTP: /stream bodies equal the containers it assembles from /header and
  /packets/{id}, in every order, with the packet orders and budget cuts it
  computes itself from the header (FORMAT.md sections 1, 2.1 and 7);
  /stream?from= payloads; /container (packet order, RFC 9110 Range and
  If-Range);
- WebSocket: containers assembled from start/packet messages equal
  /stream's and `meshwave decode` accepts them; header_only + refine,
  refine during a stream (one Done per request), resume on a new
  connection, the budget recipe that adds up to one /stream budget, errors,
  the minimum rate, and the handshake's JSON refusals.

Usage: interop_client.py --server meshwave-server --cli meshwave
           --python-protos DIR --mesh data/holes.off
Needs python3-websockets and python3-protobuf (deploy/install-deps.sh).
Exit code 0 when every check passes; each failure is printed.
"""
import argparse
import asyncio
import http.client
import json
import math
import os
import struct
import subprocess
import sys
import tempfile
import time

ORDERS = ("quality", "resolution", "rd")


class Checks:
    def __init__(self):
        self.passed = 0
        self.failed = 0

    def eq(self, got, want, what):
        if got == want:
            self.passed += 1
        else:
            self.failed += 1
            shown = lambda v: repr(v[:60]) + "... (%d bytes)" % len(v) if isinstance(v, bytes) and len(v) > 60 else repr(v)
            print("FAIL %s: got %s, want %s" % (what, shown(got), shown(want)), flush=True)

    def true(self, cond, what):
        self.eq(bool(cond), True, what)


# --- The container format (FORMAT.md section 1) -----------------------------

def varint(n):
    out = b""
    while True:
        low, n = n & 0x7F, n >> 7
        if not n:
            return out + bytes([low])
        out += bytes([low | 0x80])


def present_field(ids):
    """StreamHeader.present (field 14, packed varints); nothing when empty."""
    if not ids:
        return b""
    packed = b"".join(varint(i) for i in ids)
    return varint(14 << 3 | 2) + varint(len(packed)) + packed


def assemble(header_bytes, ids, payloads):
    """API.md "Assembling a container": the header as served (present
    empty) with `present` appended, behind the magic and its length."""
    head = header_bytes + present_field(ids)
    return b"MWV1" + struct.pack("<I", len(head)) + head + b"".join(payloads)


def container_size(header_bytes, lengths, ids):
    return 8 + len(header_bytes) + len(present_field(ids)) + sum(lengths[i] for i in ids)


def parse_container(data, pb):
    if data[:4] != b"MWV1":
        raise ValueError("bad magic")
    (h,) = struct.unpack("<I", data[4:8])
    header = pb.stream.StreamHeader()
    header.ParseFromString(data[8:8 + h])
    pos, payloads = 8 + h, []
    for i in header.present:
        n = header.packets.length[i]
        payloads.append(data[pos:pos + n])
        pos += n
    if pos != len(data):
        raise ValueError("trailing or missing bytes")
    return header, payloads


# --- Packet orders and budgets (FORMAT.md 2.1 and 7) ------------------------

class Layout:
    def __init__(self, header):
        self.h = header
        J = header.transform.levels
        self.levels = J
        self.top = [max(header.quantizers[3 * j + c].top_bitplane for c in range(3)) for j in range(J)]
        self.id = {}
        n = 0
        for j in range(J):
            for b in range(self.top[j], -1, -1):
                self.id[(j, b)] = n
                n += 1
        # Then the base refinement's packets, planes descending (FORMAT.md 3.3).
        self.base_planes = header.base.refinement_planes
        self.base = [None] * self.base_planes
        for b in range(self.base_planes - 1, -1, -1):
            self.id[("base", b)] = n
            self.base[b] = n
            n += 1
        # The original layer's parts last (FORMAT.md 2.5); this check's
        # streams have no channel or texture before it.
        self.original = []
        if header.HasField("original"):
            for part in range(2 + header.original.refinement_planes):
                self.id[("original", part)] = n
                self.original.append(n)
                n += 1
        self.jb = {v: k for k, v in self.id.items()}
        self.count = n

    def chain(self, i):
        j, _ = self.jb[i]
        if j == "original":
            return self.levels + 1
        return self.levels if j == "base" else j

    def deps(self, i):
        j, b = self.jb[i]
        if j == "original":
            return [self.original[b - 1]] if b > 0 else []
        if j == "base":
            return [self.base[b + 1]] if b + 1 < self.base_planes else []
        out = []
        if (j, b + 1) in self.id:
            out.append(self.id[(j, b + 1)])
        if self._three_xc() and (j - 1, b) in self.id:
            out.append(self.id[(j - 1, b)])
        return out

    def _three_xc(self):
        return self.h.DESCRIPTOR.fields_by_name["coder"].enum_type.values_by_number[self.h.coder].name == "CODER_3XC"

    def order(self, name, max_level=None):
        used = self.levels if max_level is None else min(max_level, self.levels)
        # Every order ends with the original layer, unless it stops at a
        # coarser level (FORMAT.md 7).
        last = self.original if used == self.levels else []
        return self._remesh_order(name, used) + last

    def _remesh_order(self, name, used):
        base = [self.base[b] for b in range(self.base_planes - 1, -1, -1)]
        if name == "resolution":
            return base + [self.id[(j, b)] for j in range(used) for b in range(self.top[j], -1, -1)]
        if name == "quality":
            # Base plane b goes just before the details' bitplane b + shift.
            top = max([self.top[j] for j in range(used)] + [-1])
            ratio = self.h.base.step / self.h.quantizers[0].step if len(self.h.quantizers) else 0
            shift = math.floor(math.log2(ratio) + 0.5) if ratio > 0 and math.isfinite(ratio) else 0
            out, b = [], self.base_planes - 1
            while b >= 0 and b + shift > top:
                out.append(self.base[b]); b -= 1
            for n in range(top, -1, -1):
                while b >= 0 and b + shift == n:
                    out.append(self.base[b]); b -= 1
                out += [self.id[(j, n)] for j in range(used) if (j, n) in self.id]
            while b >= 0:
                out.append(self.base[b]); b -= 1
            return out
        # rd: greedy on the estimated reduction per (length + 4) bytes.
        exp2 = getattr(math, "exp2", lambda x: 2.0 ** x)
        current = list(self.h.packets.chain_distortion)
        steps = self.h.packets.distortion_step
        reduction = [0.0] * self.count
        for i in range(self.count):  # chains in index order: bitplanes descending
            j = self.chain(i)
            d = steps[i]
            nxt = 0.0 if d == 255 else current[j] * exp2(-d / 32)
            reduction[i] = current[j] - nxt
            current[j] = nxt
        candidates = [self.id[(j, b)] for j in range(used) for b in range(self.top[j], -1, -1)] + base
        sent, order = set(), []
        while len(order) < len(candidates):
            best, best_value = None, None
            for i in candidates:
                if i in sent or not all(d in sent for d in self.deps(i)):
                    continue
                value = reduction[i] / (self.h.packets.length[i] + 4.0)
                if best is None or value > best_value or (value == best_value and i < best):
                    best, best_value = i, value
            sent.add(best)
            order.append(best)
        return order


def select_container(header_bytes, lengths, order, budget):
    """The longest prefix whose container fits `budget` (None: all)."""
    k = 0
    while k < len(order) and (budget is None or container_size(header_bytes, lengths, order[:k + 1]) <= budget):
        k += 1
    return k


def select_payloads(lengths, order, budget, cursor):
    k, total = cursor, 0
    while k < len(order) and (budget is None or total + lengths[order[k]] <= budget):
        total += lengths[order[k]]
        k += 1
    return k


# --- HTTP ---------------------------------------------------------------------

class Http:
    def __init__(self, port):
        self.port = port

    def get(self, target, headers=None):
        c = http.client.HTTPConnection("127.0.0.1", self.port, timeout=30)
        c.request("GET", target, headers=headers or {})
        r = c.getresponse()
        body = r.read()
        c.close()
        return r.status, {k.lower(): v for k, v in r.getheaders()}, body


def check_http(ck, web, mesh_id, header_bytes, header, layout, packets, full):
    base = "/v1/meshes/" + mesh_id
    lengths = header.packets.length
    for name in ORDERS:
        order = layout.order(name)
        for budget in (None, 3000, 7000, 20000):
            what = "%s budget %s" % (name, budget)
            q = "?order=" + name + ("" if budget is None else "&budget=%d" % budget)
            status, hdrs, body = web.get(base + "/stream" + q)
            ck.eq(status, 200, "/stream " + what)
            k = select_container(header_bytes, lengths, order, budget)
            ck.eq(int(hdrs.get("x-meshwave-next-cursor", -1)), k, "/stream next cursor " + what)
            ck.eq(hdrs.get("x-meshwave-complete"), "true" if k == len(order) else "false", "complete " + what)
            ids = order[:k]
            ck.eq(body, assemble(header_bytes, ids, [packets[i] for i in ids]), "/stream = /header + /packets, " + what)
            # Re-serializing with protobuf gives the same head, `present`
            # being the last field, in field order only where fields above
            # 14 (channels, texture, original) come before it (FORMAT.md 1).
            h2 = pb.stream.StreamHeader()
            h2.ParseFromString(header_bytes)
            h2.present.extend(ids)
            h3 = pb.stream.StreamHeader()
            h3.ParseFromString(header_bytes + present_field(ids))
            ck.eq(h3, h2, "present appended parses as the serialized header, " + what)
            if not (h2.channels or h2.HasField("texture") or h2.HasField("original")):
                ck.eq(h2.SerializeToString(), header_bytes + present_field(ids), "present appended = serialized, " + what)
        for cursor, budget in ((1, 2000), (5, 5000), (len(order) - 1, None)):
            status, hdrs, body = web.get(base + "/stream?order=%s&from=%d%s" % (
                name, cursor, "" if budget is None else "&budget=%d" % budget))
            k = select_payloads(lengths, order, budget, cursor)
            ck.eq(body, b"".join(packets[i] for i in order[cursor:k]), "/stream?from=%d %s" % (cursor, name))
            ck.eq(int(hdrs.get("x-meshwave-next-cursor", -1)), k, "from next cursor")
    status, _, body = web.get(base + "/stream?order=rd&budget=10")
    ck.eq(status, 400, "a budget below the header")
    ck.true(b"smaller than the stream header" in body, "its message")

    # /container: every packet, in id order.
    parsed, payloads = parse_container(full, pb)
    ck.eq(list(parsed.present), list(range(layout.count)), "/container packet order: ids 0..N-1")
    ck.eq(full, assemble(header_bytes, list(range(layout.count)), [packets[i] for i in range(layout.count)]),
          "/container = /header + every /packets in id order")

    # Range (RFC 9110 section 14), from the bytes of /container.
    size = len(full)
    cases = [("bytes=0-499", 0, 499), ("bytes=500-999", 500, 999), ("bytes=-500", size - 500, size - 1),
             ("bytes=%d-" % (size - 500), size - 500, size - 1), ("bytes=500-600,601-999", 500, 999),
             ("bytes=500-700,601-999", 500, 999), ("BYTES=0-5", 0, 5), ("bytes=0-5,", 0, 5),
             ("bytes= 0-5", 0, 5), ("bytes=100-99999999999", 100, size - 1)]
    for rng, a, b in cases:
        status, hdrs, body = web.get(base + "/container", {"Range": rng})
        ck.eq(status, 206, "Range " + rng)
        ck.eq(body, full[a:b + 1], "Range body " + rng)
        ck.eq(hdrs.get("content-range"), "bytes %d-%d/%d" % (a, b, size), "Content-Range " + rng)
    status, hdrs, body = web.get(base + "/container", {"Range": "bytes=0-0,-1"})
    ck.eq((status, body), (200, full), "two disjoint ranges: the whole")
    for rng, text in (("bytes=abc", "not first-last"), ("bytes=%d-" % size, "starts inside"),
                      ("bytes=9-3", "ends before it starts")):
        status, hdrs, body = web.get(base + "/container", {"Range": rng})
        ck.eq(status, 416, "Range " + rng)
        ck.eq(hdrs.get("content-range"), "bytes */%d" % size, "416 Content-Range " + rng)
        ck.true(text in json.loads(body)["error"], "416 says why: " + rng)
    etag = web.get(base + "/container")[1]["etag"]
    status, _, body = web.get(base + "/container", {"Range": "bytes=0-9", "If-Range": etag})
    ck.eq((status, body), (206, full[:10]), "If-Range with the ETag")
    for other in ("W/" + etag, '"other"', "Sun, 06 Nov 1994 08:49:37 GMT"):
        status, _, body = web.get(base + "/container", {"Range": "bytes=0-9", "If-Range": other})
        ck.eq((status, body), (200, full), "If-Range " + other)


# --- WebSocket ----------------------------------------------------------------

def client_message(**kw):
    m = pb.ws.ClientMessage()
    kind = kw.pop("kind")
    sub = getattr(m, kind)
    sub.SetInParent()
    for k, v in kw.items():
        if v is not None:
            setattr(sub, k, v)
    return m.SerializeToString()


async def read_until_done(ws, dones=1):
    """The messages of one exchange, through `dones` Done messages."""
    out = []
    while dones:
        m = pb.ws.ServerMessage()
        m.ParseFromString(await asyncio.wait_for(ws.recv(), 30))
        out.append(m)
        if m.HasField("done"):
            dones -= 1
        if m.HasField("error") and dones == 1 and not any(x.HasField("done") for x in out):
            break
    return out


def assemble_ws(messages):
    """API.md: StreamStart's header, then each Packet's id into `present`
    and payload after the header, in arrival order."""
    header, ids, payloads = None, [], []
    for m in messages:
        if m.HasField("start"):
            header = m.start.header
        elif m.HasField("packet"):
            ids.append(m.packet.id)
            payloads.append(m.packet.payload)
    return assemble(header, ids, payloads), ids, payloads


async def check_ws(ck, port, web, mesh_id, header_bytes, header, layout, packets, cli, work):
    import websockets
    url = "ws://127.0.0.1:%d/v1/ws" % port
    base = "/v1/meshes/" + mesh_id
    lengths = header.packets.length
    mid = mesh_id.encode()
    async with websockets.connect(url, max_size=None) as ws:
        for name in ORDERS:
            for budget in (None, 3000, 9000):
                what = "ws %s budget %s" % (name, budget)
                await ws.send(client_message(kind="start", mesh_id=mid, order=name.encode(), budget=budget))
                msgs = await read_until_done(ws)
                data, ids, _ = assemble_ws(msgs)
                body = web.get(base + "/stream?order=" + name + ("" if budget is None else "&budget=%d" % budget))[2]
                ck.eq(data, body, "assembled WebSocket container = /stream, " + what)
                ck.eq(msgs[0].start.selection.bytes, len(body), "Selection.bytes " + what)
                ck.eq(sum(m.HasField("done") for m in msgs), 1, "one Done " + what)
                if budget == 9000:
                    path = os.path.join(work, "ws_%s.mwv" % name)
                    with open(path, "wb") as f:
                        f.write(data)
                    r = subprocess.run([cli, "decode", path, os.path.join(work, "ws_%s.ply" % name)],
                                       capture_output=True, text=True)
                    ck.eq(r.returncode, 0, "meshwave decode accepts the assembled %s container: %s" % (name, r.stderr))

        # Budgets: each request's own. The recipe of API.md ("Budgets") gives
        # exactly /stream?budget=T after a start with B < T, in every order.
        for name in ORDERS:
            order = layout.order(name)
            for b1, total in ((2500, 6000), (4000, 15000)):
                await ws.send(client_message(kind="start", mesh_id=mid, order=name.encode(), budget=b1))
                first = await read_until_done(ws)
                k1 = first[-1].done.next_cursor
                target = select_container(header_bytes, lengths, order, total)
                extra = sum(lengths[i] for i in order[k1:target])
                msgs = first
                if extra:
                    await ws.send(client_message(kind="refine", extra_bytes=extra))
                    msgs = first + await read_until_done(ws)
                data, _, _ = assemble_ws(msgs)
                ck.eq(data, web.get(base + "/stream?order=%s&budget=%d" % (name, total))[2],
                      "start %d + refine to %d = /stream?budget=%d, %s" % (b1, total, total, name))
                # What a plain refine of T - B gets: documented, and computable.
                await ws.send(client_message(kind="refine", extra_bytes=total - b1))
                more = await read_until_done(ws)
                sel = more[0].selection
                ck.eq(sel.next_cursor, select_payloads(lengths, order, total - b1, sel.from_cursor),
                      "refine(T - B) selects payloads fitting T - B from the end, " + name)

        # header_only, then refine: payloads of order[0..] fitting the refine.
        order = layout.order("quality")
        await ws.send(client_message(kind="start", mesh_id=mid, header_only=True))
        msgs = await read_until_done(ws)
        ck.eq(msgs[0].start.header, header_bytes, "header_only header = /header")
        ck.eq([m.WhichOneof("message") for m in msgs], ["start", "done"], "header_only: start, done")
        await ws.send(client_message(kind="refine", extra_bytes=3000))
        msgs = await read_until_done(ws)
        k = select_payloads(lengths, order, 3000, 0)
        ck.eq([m.packet.id for m in msgs if m.HasField("packet")], order[:k], "refine after header_only")

        # A refine while a stream runs: one Done for each request, in order.
        await ws.send(client_message(kind="start", mesh_id=mid, order=b"resolution", budget=6000, rate=20000))
        await ws.send(client_message(kind="refine", extra_bytes=2000))
        msgs = await read_until_done(ws, dones=2)
        dones = [m.done for m in msgs if m.HasField("done")]
        sels = [m.selection for m in msgs if m.HasField("selection")]
        order = layout.order("resolution")
        k1 = select_container(header_bytes, lengths, order, 6000)
        k2 = select_payloads(lengths, order, 2000, k1)
        ck.eq([d.next_cursor for d in dones], [k1, k2], "two Dones, at the start's end and the refine's")
        ck.eq([(s.from_cursor, s.next_cursor) for s in sels], [(k1, k2)], "the refine's selection")
        ck.eq([m.packet.cursor for m in msgs if m.HasField("packet")], list(range(k2)), "packets in cursor order")

        # Errors keep the connection open.
        for kw, text in (({"mesh_id": b"\xff\xfe\x80notutf8"}, "invalid mesh id"),
                         ({"mesh_id": b"0123456789ab"}, "no mesh"),
                         ({"mesh_id": mid, "order": b"best"}, "unknown order"),
                         ({"mesh_id": mid, "rate": 1}, "below the minimum")):
            await ws.send(client_message(kind="start", **kw))
            m = pb.ws.ServerMessage()
            m.ParseFromString(await asyncio.wait_for(ws.recv(), 30))
            ck.true(m.HasField("error") and text in m.error.message, "error: " + text)

    # Resume on a new connection: payloads from a cursor, as /stream?from=.
    async with websockets.connect(url, max_size=None) as ws:
        await ws.send(client_message(kind="resume", mesh_id=mid, order=b"rd", cursor=4, budget=5000))
        msgs = await read_until_done(ws)
        body = web.get(base + "/stream?order=rd&from=4&budget=5000")[2]
        ck.eq(b"".join(m.packet.payload for m in msgs if m.HasField("packet")), body, "resume = /stream?from=4")


def check_handshake(ck, port):
    """Refused upgrades are JSON errors, as every other error."""
    up = {"Connection": "Upgrade", "Upgrade": "websocket", "Sec-WebSocket-Version": "13",
          "Sec-WebSocket-Key": "dGhlIHNhbXBsZSBub25jZQ=="}
    cases = (("/v1/ws/", up, 404), ("/v1/ws?x=1", up, 400), ("/v1/wsx", up, 404),
             ("/v1/ws", dict(up, **{"Sec-WebSocket-Version": "12"}), 426),
             ("/v1/ws", {k: v for k, v in up.items() if k != "Sec-WebSocket-Key"}, 400))
    for target, headers, want in cases:
        status, hdrs, body = Http(port).get(target, headers)
        what = "upgrade %s %s" % (target, headers.get("Sec-WebSocket-Version"))
        ck.eq(status, want, what)
        ck.eq(hdrs.get("content-type"), "application/json", "JSON content type, " + what)
        try:
            ck.true(json.loads(body)["error"], "JSON error body, " + what)
        except ValueError:
            ck.true(False, "JSON error body, %s: %r" % (what, body))
        if want == 426:
            ck.eq(hdrs.get("sec-websocket-version"), "13", "426 names the version")


class Server:
    def __init__(self, exe, mesh, work):
        catalog = os.path.join(work, "catalog")
        subprocess.run([exe, "ingest", "--catalog", catalog, mesh], check=True,
                       stdout=subprocess.DEVNULL)
        port_file = os.path.join(work, "port")
        self.log = open(os.path.join(work, "server.log"), "w")
        self.proc = subprocess.Popen([exe, "--catalog", catalog, "--listen", "127.0.0.1:0",
                                      "--port-file", port_file], stdout=self.log, stderr=subprocess.STDOUT)
        for _ in range(300):
            if os.path.exists(port_file) and open(port_file).read().strip():
                self.port = int(open(port_file).read())
                return
            if self.proc.poll() is not None:
                raise RuntimeError("meshwave-server exited")
            time.sleep(0.05)
        raise RuntimeError("meshwave-server did not start")

    def stop(self):
        self.proc.terminate()
        self.proc.wait(30)
        self.log.close()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--server", required=True, help="meshwave-server binary")
    ap.add_argument("--cli", required=True, help="meshwave binary (decode)")
    ap.add_argument("--python-protos", required=True, help="directory of the *_pb2.py modules")
    ap.add_argument("--mesh", required=True, help="a mesh file to ingest")
    args = ap.parse_args()
    sys.path.insert(0, args.python_protos)
    global pb
    import stream_pb2
    import websocket_pb2
    import catalog_api_pb2

    class pb:
        stream = stream_pb2
        ws = websocket_pb2
        catalog = catalog_api_pb2

    ck = Checks()
    with tempfile.TemporaryDirectory(prefix="meshwave-interop-") as work:
        server = Server(args.server, args.mesh, work)
        try:
            web = Http(server.port)
            listing = json.loads(web.get("/v1/meshes")[2])
            mesh_id = listing["meshes"][0]["id"]
            header_bytes = web.get("/v1/meshes/%s/header" % mesh_id)[2]
            header = pb.stream.StreamHeader()
            header.ParseFromString(header_bytes)
            layout = Layout(header)
            packets = [web.get("/v1/meshes/%s/packets/%d" % (mesh_id, i))[2] for i in range(layout.count)]
            ck.eq([len(p) for p in packets], list(header.packets.length), "packet lengths = the index")
            full = web.get("/v1/meshes/%s/container" % mesh_id)[2]
            check_http(ck, web, mesh_id, header_bytes, header, layout, packets, full)
            asyncio.run(check_ws(ck, server.port, web, mesh_id, header_bytes, header, layout, packets,
                                 args.cli, work))
            check_handshake(ck, server.port)
        finally:
            server.stop()
    print("%d checks passed, %d failed" % (ck.passed, ck.failed))
    return 1 if ck.failed else 0


if __name__ == "__main__":
    sys.exit(main())
