#include "upload_handler.h"

#include <openssl/crypto.h>
#include <spdlog/spdlog.h>

#include "ingest.h"
#include "mesh_handlers.h"
#include "meshwave/request_target.h"
#include "multipart_form.h"
#include "response.h"
#include "upload_files.h"
#include "upload_worker.h"

namespace meshwave::server {
namespace {

constexpr size_t kMaxNameLength = 200;
// POST ?fidelity=: at most this many dB, and a remesh of at most this many
// finest vertices per uploaded vertex (the default density is about 1).
constexpr uint64_t kMaxUploadFidelityDb = 150;
constexpr double kUploadMaxVertexRatio = 4;

// The format of a single-file upload: ?format= when given, else from its
// first bytes (the binary glTF magic, "ply", an OFF header keyword), else
// OBJ (which has no magic). A JSON glTF needs format=gltf (and its buffers
// as data URIs: a single body has no other files).
Result<std::string> UploadExtension(const QueryParams& query, std::string_view body) {
  if (auto f = query.Get("format")) {
    for (const char* known : {"ply", "obj", "off", "glb", "gltf"}) {
      if (*f == known) return "." + *f;
    }
    return InvalidArgument("unknown format '" + *f + "' (ply, obj, off, glb, gltf)");
  }
  if (body.starts_with("glTF")) return std::string(".glb");
  if (body.starts_with("ply")) return std::string(".ply");
  size_t i = 0;
  while (i < body.size() && (body[i] == ' ' || body[i] == '\n' || body[i] == '\r' || body[i] == '\t')) ++i;
  const std::string_view head = body.substr(i, 8);
  for (std::string_view off : {"OFF", "COFF", "NOFF", "CNOFF"}) {
    if (head.starts_with(off)) return std::string(".off");
  }
  return std::string(".obj");
}

// The upload's ingest: in a worker process at lower priority when the
// server knows where its catalog is (always, but for the fuzz harness),
// else here. `boundary` empty: the body is the file `source`; else a
// multipart body whose main file is `source` (FilesOfMultipart).
Result<UploadOutcome> Ingest(ServerContext& ctx, std::string_view bytes, const std::string& name,
                             const std::string& source, const std::string& boundary,
                             const EncodeChoices& choices) {
  if (!ctx.catalog_location().empty()) {
    WorkerOptions options;
    options.nice = static_cast<int>(ctx.config().ingest_nice());
    options.memory_limit_bytes = ctx.config().ingest_memory_limit_bytes();
    return IngestInWorker(ctx.catalog_location(), ctx.store_location(), bytes, name, source,
                          boundary, choices, options);
  }
  MW_ASSIGN_OR_RETURN(IngestResult result,
                      IngestUpload(ctx.catalog(), bytes, name, source, boundary, choices));
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
  if (Status s = query.CheckAllowed({"name", "format", "fidelity", "main"}); !s.ok()) {
    return done(StatusError(s));
  }
  // fidelity=DB: the complete stream's surface PSNR to reach against the
  // upload; the remesh may grow to kUploadMaxVertexRatio times the
  // upload's vertices for it, and no further (an upload bounds its cost).
  EncodeChoices choices;
  // One upload is ingested at a time; it uses the server's configured
  // threads, not every core of the machine.
  choices.threads = static_cast<int>(ctx.config().threads());
  choices.limits = UploadAssetLimits(ctx.config());
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
  std::string source;    // the main file's name in the original
  std::string boundary;  // empty: the body is the one file
  if (IsMultipartFormData(req[http::field::content_type])) {
    if (query.Get("format")) {
      return done(JsonError(http::status::bad_request,
                            "format= is for a single-file body; the parts of a multipart body "
                            "are known by their filenames"));
    }
    auto b = MultipartBoundary(req[http::field::content_type]);
    if (!b.ok()) return done(StatusError(b.status()));
    // Checked here, before any work is queued: a malformed body, a bad or
    // repeated name or an unclear main file is the client's to fix.
    auto files = FilesOfMultipart(req.body(), *b, query.Get("main"));
    if (!files.ok()) {
      return done(files.status().code() == StatusCode::kNotFound
                      ? JsonError(http::status::unprocessable_entity, files.status().message())
                      : StatusError(files.status()));
    }
    source = files->main;
    boundary = *b;
  } else {
    if (query.Get("main")) {
      return done(JsonError(http::status::bad_request,
                            "main= names a part of a multipart/form-data body; this body is "
                            "one file"));
    }
    auto ext = UploadExtension(query, req.body());
    if (!ext.ok()) return done(StatusError(ext.status()));
    source = name + *ext;
  }
  net::post(ctx.ingest_pool(), [&ctx, req = std::move(req), name, source, boundary, choices,
                                done = std::move(done)]() mutable {
    Response r;
    try {
      auto outcome = Ingest(ctx, req.body(), name, source, boundary, choices);
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
