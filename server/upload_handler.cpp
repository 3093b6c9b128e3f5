#include "upload_handler.h"

#include <openssl/crypto.h>
#include <spdlog/spdlog.h>

#include "ingest.h"
#include "upload_worker.h"
#include "mesh_handlers.h"
#include "meshwave/request_target.h"
#include "response.h"
#include "meshwave/mesh_io.h"

namespace meshwave::server {
namespace {

constexpr size_t kMaxNameLength = 200;
// POST ?fidelity=: at most this many dB, and a remesh of at most this many
// finest vertices per uploaded vertex (the default density is about 1).
constexpr uint64_t kMaxUploadFidelityDb = 150;
constexpr double kUploadMaxVertexRatio = 4;

// The format of an uploaded mesh: ?format= when given, else from its first
// bytes ("ply", an OFF header keyword), else OBJ (which has no magic).
Result<MeshFormat> UploadFormat(const QueryParams& query, std::string_view body) {
  if (auto f = query.Get("format")) {
    if (*f == "ply") return MeshFormat::kPly;
    if (*f == "obj") return MeshFormat::kObj;
    if (*f == "off") return MeshFormat::kOff;
    return InvalidArgument("unknown format '" + *f + "' (ply, obj, off)");
  }
  if (body.starts_with("ply")) return MeshFormat::kPly;
  size_t i = 0;
  while (i < body.size() && (body[i] == ' ' || body[i] == '\n' || body[i] == '\r' || body[i] == '\t')) ++i;
  const std::string_view head = body.substr(i, 8);
  for (std::string_view off : {"OFF", "COFF", "NOFF", "CNOFF"}) {
    if (head.starts_with(off)) return MeshFormat::kOff;
  }
  return MeshFormat::kObj;
}

// The upload's ingest: in a worker process at lower priority when the
// server knows where its catalog is (always, but for the fuzz harness),
// else here.
Result<UploadOutcome> Ingest(ServerContext& ctx, std::string_view bytes, const std::string& name,
                             const std::string& source, const EncodeChoices& choices) {
  if (!ctx.catalog_location().empty()) {
    WorkerOptions options;
    options.nice = static_cast<int>(ctx.config().ingest_nice());
    options.memory_limit_bytes = ctx.config().ingest_memory_limit_bytes();
    return IngestInWorker(ctx.catalog_location(), ctx.store_location(), bytes, name, source,
                          choices, options);
  }
  MW_ASSIGN_OR_RETURN(IngestResult result,
                      IngestMeshBytes(ctx.catalog(), bytes, name, source, choices));
  return UploadOutcome{result.entry.id, result.already_present, result.remeshed,
                       result.fidelity_db};
}

Status CheckName(const std::string& name) {
  if (name.empty() || name.size() > kMaxNameLength) {
    return InvalidArgument("name must have 1 to " + std::to_string(kMaxNameLength) + " bytes");
  }
  for (char c : name) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      return InvalidArgument("name holds a control character");
    }
  }
  return Status::Ok();
}

}  // namespace

std::optional<Response> CheckAuthorization(const ServerContext& ctx,
                                           const http::request_header<>& header) {
  const std::string& token = ctx.config().upload_token();
  const auto auth = header[http::field::authorization];
  if (auth.empty() || !auth.starts_with("Bearer ")) {
    Response r = JsonError(http::status::unauthorized, "a bearer token is required");
    r.set(http::field::www_authenticate, "Bearer realm=\"meshwave\"");
    return r;
  }
  if (token.empty()) {
    return JsonError(http::status::forbidden, "uploads are disabled on this server");
  }
  const std::string_view given = auth.substr(7);
  // Constant time, so the token cannot be guessed byte by byte.
  if (given.size() != token.size() ||
      CRYPTO_memcmp(given.data(), token.data(), token.size()) != 0) {
    return JsonError(http::status::forbidden, "the bearer token is not valid");
  }
  return std::nullopt;
}

void UploadMesh(ServerContext& ctx, Request req, const QueryParams& query,
                std::function<void(Response)> done) {
  if (Status s = query.CheckAllowed({"name", "format", "fidelity"}); !s.ok()) {
    return done(StatusError(s));
  }
  // fidelity=DB: the complete stream's surface PSNR to reach against the
  // upload; the remesh may grow to kUploadMaxVertexRatio times the
  // upload's vertices for it, and no further (an upload bounds its cost).
  EncodeChoices choices;
  // One upload is ingested at a time; it uses the server's configured
  // threads, not every core of the machine.
  choices.threads = static_cast<int>(ctx.config().threads());
  if (auto f = query.Get("fidelity")) {
    auto db = ParseUnsigned(*f, kMaxUploadFidelityDb, "fidelity");
    if (!db.ok()) return done(StatusError(db.status()));
    choices.fidelity_db = static_cast<double>(*db);  // 0: one remesh, no fidelity
    choices.max_vertex_ratio = kUploadMaxVertexRatio;
  }
  if (req.body().empty()) {
    return done(JsonError(http::status::bad_request, "the request body (a mesh file) is empty"));
  }
  const std::string name = query.Get("name").value_or("upload");
  if (Status s = CheckName(name); !s.ok()) return done(StatusError(s));
  auto format = UploadFormat(query, req.body());
  if (!format.ok()) return done(StatusError(format.status()));
  const char* ext = *format == MeshFormat::kPly ? ".ply" : *format == MeshFormat::kOff ? ".off" : ".obj";
  net::post(ctx.ingest_pool(), [&ctx, req = std::move(req), name, ext, choices,
                                done = std::move(done)]() mutable {
    Response r;
    try {
      auto outcome = Ingest(ctx, req.body(), name, name + ext, choices);
      Result<std::optional<CatalogEntry>> entry =
          outcome.ok() ? ctx.catalog().Find(outcome->id) : outcome.status();
      if (entry.ok() && !*entry) {
        entry = Status(StatusCode::kInternal, "the ingested mesh " + outcome->id +
                                                  " is not in the catalog");
      }
      if (!entry.ok()) {
        const auto code = entry.status().code();
        r = code == StatusCode::kIoError || code == StatusCode::kInternal
                ? JsonError(http::status::internal_server_error, entry.status().message())
                : JsonError(http::status::unprocessable_entity, entry.status().message());
      } else {
        const CatalogEntry& e = **entry;
        proto::MeshSummary summary;
        ToProto(e, summary);
        r = Message(req, summary, outcome->already_present ? http::status::ok
                                                           : http::status::created);
        r.set(http::field::location, "/v1/meshes/" + e.id);
        spdlog::info("uploaded {} as {} ({} bytes{})", name, e.id, e.bytes,
                     outcome->remeshed ? ", remeshed" : "");
      }
    } catch (const std::exception& e) {  // e.g. bad_alloc on a huge mesh
      r = JsonError(http::status::internal_server_error, std::string("ingest failed: ") + e.what());
    }
    done(std::move(r));
  });
}

Response DeleteMesh(ServerContext& ctx, const std::string& id) {
  auto removed = RemoveEntry(ctx.catalog(), id);
  if (!removed.ok()) return StatusError(removed.status());
  if (!*removed) return JsonError(http::status::not_found, "no mesh with id " + id);
  ctx.cache().Evict(id);  // retires the mesh: the response cache no longer serves it
  ctx.response_cache().EraseRetired();
  spdlog::info("deleted {}", id);
  return Response{http::status::no_content, 11};
}

}  // namespace meshwave::server
