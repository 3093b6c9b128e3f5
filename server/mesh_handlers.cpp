#include "mesh_handlers.h"

#include "byte_range.h"
#include "etag.h"
#include "meshwave/container.h"
#include "meshwave/region_text.h"
#include "meshwave/stream_request.h"
#include "meshwave/stream_units.h"
#include "response.h"
#include "sha256.h"
#include "stream_cursor.h"

namespace meshwave::server {
namespace {

constexpr uint64_t kDefaultListLimit = 100;
constexpr uint64_t kMaxListLimit = 1000;

// The served mesh, or the error response to send instead.
struct Lookup {
  std::shared_ptr<const ServedMesh> mesh;
  Response error;
};

Lookup Find(ServerContext& ctx, const std::string& id) {
  Lookup l;
  auto mesh = ctx.cache().Get(id);
  if (!mesh.ok()) {
    l.error = JsonError(http::status::internal_server_error,
                        "mesh " + id + " cannot be served: " + mesh.status().message());
  } else if (!*mesh) {
    l.error = JsonError(http::status::not_found, "no mesh with id " + id);
  } else {
    l.mesh = std::move(*mesh);
  }
  return l;
}

// 304 when If-None-Match matches, else null.
bool NotModified(const Request& req, const std::string& etag, Response& out) {
  const auto inm = req[http::field::if_none_match];
  if (inm.empty() || !IfNoneMatchMatches(inm, etag)) return false;
  out = Response{http::status::not_modified, 11};
  MarkImmutable(out, etag);
  return true;
}

Response Binary(const std::shared_ptr<const ServedMesh>& mesh, const std::string& etag) {
  Response r{http::status::ok, 11};
  r.set(http::field::content_type, "application/octet-stream");
  r.body().mesh = mesh;
  MarkImmutable(r, etag);
  return r;
}

// A region request (docs/API.md, "Region requests"): unit records of what
// the client lacks, in the region's (or the uniform order's) order.
Response GetUnits(const Request& req, const std::shared_ptr<const ServedMesh>& mesh,
                  const StreamRequest& q) {
  const ServedMesh& m = *mesh;
  StreamCursor cursor;
  // The header is never in the body: the budget counts payloads.
  auto s = cursor.Start(mesh, q, /*with_header=*/false);
  if (!s.ok()) return StatusError(s.status());
  // The bytes depend on what is held, the order or region, the level limit
  // and how many units fitted.
  const size_t units = s->next - s->from;
  const std::string key =
      std::string(ProgressionName(q.order)) + "|" + (q.region ? FormatRegionShape(*q.region) : "") +
      "|" + std::to_string(q.max_level) + "|" + q.held.value_or("") + "|" + std::to_string(units);
  const std::string etag = StrongEtag(m.entry().sha256, "u-" + Sha256Hex(key).substr(0, 32));
  Response r;
  if (!NotModified(req, etag, r)) {
    r = Binary(mesh, etag);
    r.set(http::field::content_type, "application/vnd.meshwave.units");
    std::string& body = r.body().owned;
    body.reserve(s->bytes + 12 * units);
    for (auto u = cursor.Peek(); u; cursor.Advance(), u = cursor.Peek()) {
      AppendUnitRecord(body, u->unit, u->payload);
    }
  }
  r.set("X-Meshwave-Units", std::to_string(units));
  r.set("X-Meshwave-Complete", s->complete ? "true" : "false");
  return r;
}

}  // namespace

void ToProto(const CatalogEntry& e, proto::MeshSummary& out) {
  out.set_id(e.id);
  out.set_name(e.name);
  out.set_source(e.source);
  out.set_vertices(e.vertices);
  out.set_faces(e.faces);
  out.set_levels(e.levels);
  out.set_packets(e.packets);
  out.set_bytes(e.bytes);
  out.set_sha256(e.sha256);
  out.set_created_unix(e.created_unix);
  out.set_format_version(e.format_version);
  out.set_settings(e.settings);
  out.set_has_original(!e.original.empty());
}

Response ListMeshes(ServerContext& ctx, const Request& req, const QueryParams& query) {
  if (Status s = query.CheckAllowed({"limit", "offset"}); !s.ok()) return StatusError(s);
  uint64_t limit = kDefaultListLimit, offset = 0;
  if (auto v = query.Get("limit")) {
    auto l = ParseUnsigned(*v, kMaxListLimit, "limit");
    if (!l.ok()) return StatusError(l.status());
    limit = *l;
  }
  if (auto v = query.Get("offset")) {
    auto o = ParseUnsigned(*v, uint64_t{1} << 62, "offset");
    if (!o.ok()) return StatusError(o.status());
    offset = *o;
  }
  auto entries = ctx.catalog().List(limit, offset);
  if (!entries.ok()) return StatusError(entries.status());
  auto total = ctx.catalog().Count();
  if (!total.ok()) return StatusError(total.status());
  proto::MeshList list;
  for (const auto& e : *entries) ToProto(e, *list.add_meshes());
  list.set_total(*total);
  list.set_offset(offset);
  list.set_limit(limit);
  Response r = Message(req, list);
  r.set(http::field::cache_control, "no-cache");
  return r;
}

Response DescribeMesh(ServerContext& ctx, const Request& req, const std::string& id) {
  Lookup l = Find(ctx, id);
  if (!l.mesh) return std::move(l.error);
  const ServedMesh& m = *l.mesh;
  proto::MeshDetails d;
  ToProto(m.entry(), *d.mutable_mesh());
  d.set_header_bytes(m.entry().bytes - m.payload_bytes());
  d.set_payload_bytes(m.payload_bytes());
  d.set_base_vertices(m.header().base.vertex_count);
  d.set_base_faces(m.header().base.face_count);
  for (Progression p : {Progression::kQuality, Progression::kResolution, Progression::kRd}) {
    auto* o = d.add_orders();
    o->set_name(ProgressionName(p));
    o->set_packets(static_cast<uint32_t>(m.Order(p, -1).size()));
  }
  for (const auto& point : m.rd_table()) {
    auto* p = d.add_rate_distortion();
    p->set_packets(point.packets);
    p->set_bytes(point.bytes);
    // JSON has no infinity: a lossless prefix reports 999 dB.
    p->set_psnr_db(std::isfinite(point.psnr_db) ? point.psnr_db : 999.0);
  }
  const std::string etag = StrongEtag(m.entry().sha256, "info");
  Response r;
  if (NotModified(req, etag, r)) return r;
  r = Message(req, d);
  MarkImmutable(r, etag);
  r.set(http::field::vary, "Accept");
  return r;
}

Response GetHeader(ServerContext& ctx, const Request& req, const std::string& id) {
  Lookup l = Find(ctx, id);
  if (!l.mesh) return std::move(l.error);
  const std::string etag = StrongEtag(l.mesh->entry().sha256, "header");
  Response r;
  if (NotModified(req, etag, r)) return r;
  r = Binary(l.mesh, etag);
  r.set(http::field::content_type, kProtobufType);
  r.body().AddSlice(l.mesh->header_bytes());
  return r;
}

Response GetStream(ServerContext& ctx, const Request& req, const std::string& id,
                   const QueryParams& query) {
  auto q = ParseStreamQuery(query);
  if (!q.ok()) return StatusError(q.status());
  Lookup l = Find(ctx, id);
  if (!l.mesh) return std::move(l.error);
  if (q->units()) return GetUnits(req, l.mesh, *q);
  const ServedMesh& m = *l.mesh;
  StreamCursor cursor;
  // From cursor 0 the body is a container: the budget counts its header.
  auto s = cursor.Start(l.mesh, *q, /*with_header=*/q->from == 0);
  if (!s.ok()) return StatusError(s.status());
  // The response bytes depend only on these four numbers.
  const std::string variant = std::string("s-") + ProgressionName(q->order) + "-" +
                              (q->max_level < 0 ? std::string("all") : std::to_string(q->max_level)) + "-" + std::to_string(q->from) +
                              "-" + std::to_string(s->next);
  const std::string etag = StrongEtag(m.entry().sha256, variant);
  Response r;
  if (!NotModified(req, etag, r)) {
    r = Binary(l.mesh, etag);
    std::vector<uint32_t> ids;
    for (auto u = cursor.Peek(); u; cursor.Advance(), u = cursor.Peek()) {
      ids.push_back(u->unit.id);
      r.body().AddSlice(u->payload);
    }
    if (q->from == 0) {
      r.set(http::field::content_type, "application/vnd.meshwave.mwv");
      r.body().owned = SerializeContainerHead(m.header_bytes(), ids);
    }
  }
  r.set("X-Meshwave-Packets", std::to_string(s->next - s->from));
  r.set("X-Meshwave-Next-Cursor", std::to_string(s->next));
  r.set("X-Meshwave-Complete", s->complete ? "true" : "false");
  return r;
}

Response GetPacket(ServerContext& ctx, const Request& req, const std::string& id,
                   const std::string& packet) {
  auto k = ParseUnsigned(packet, 0xffffffffu, "packet number");
  if (!k.ok()) return StatusError(k.status());
  Lookup l = Find(ctx, id);
  if (!l.mesh) return std::move(l.error);
  if (*k >= l.mesh->packet_count()) {
    return JsonError(http::status::not_found,
                     "mesh " + id + " has " + std::to_string(l.mesh->packet_count()) +
                         " packets, no packet " + packet);
  }
  const std::string etag = StrongEtag(l.mesh->entry().sha256, "p" + packet);
  Response r;
  if (NotModified(req, etag, r)) return r;
  r = Binary(l.mesh, etag);
  r.body().AddSlice(l.mesh->payload(static_cast<uint32_t>(*k)));
  return r;
}

Response GetContainer(ServerContext& ctx, const Request& req, const std::string& id) {
  Lookup l = Find(ctx, id);
  if (!l.mesh) return std::move(l.error);
  const std::string etag = StrongEtag(l.mesh->entry().sha256, "");
  Response r;
  if (NotModified(req, etag, r)) return r;
  const std::string_view bytes = l.mesh->map()->bytes();
  // RFC 9110 13.2.2: If-None-Match first (above), then If-Range decides
  // whether Range applies at all; a failed If-Range means the whole.
  const auto range_header = req[http::field::range];
  const auto if_range = req[http::field::if_range];
  const bool use_range =
      !range_header.empty() && (if_range.empty() || IfRangeHolds(if_range, etag));
  const RangeRequest range = use_range ? ParseRange(range_header, bytes.size()) : RangeRequest{};
  if (range.kind == RangeRequest::kUnsatisfiable) {
    r = JsonError(http::status::range_not_satisfiable, range.problem);
    r.set(http::field::content_range, "bytes */" + std::to_string(bytes.size()));
    return r;
  }
  r = Binary(l.mesh, etag);
  r.set(http::field::content_type, "application/vnd.meshwave.mwv");
  r.set(http::field::accept_ranges, "bytes");
  if (range.kind == RangeRequest::kPartial) {
    r.result(http::status::partial_content);
    r.set(http::field::content_range, "bytes " + std::to_string(range.first) + "-" +
                                          std::to_string(range.last) + "/" +
                                          std::to_string(bytes.size()));
    r.body().AddSlice(bytes.substr(range.first, range.last - range.first + 1));
  } else {
    r.body().AddSlice(bytes);
  }
  return r;
}

}  // namespace meshwave::server
