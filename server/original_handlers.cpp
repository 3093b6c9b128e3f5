#include "original_handlers.h"

#include "catalog_api.pb.h"
#include "response.h"
#include "upload_handler.h"

namespace meshwave::server {

Response GetOriginal(ServerContext& ctx, const Request& req, const std::string& id,
                     std::string_view file) {
  Response r = [&]() -> Response {
    if (auto refusal = CheckAuthorization(ctx, req)) return std::move(*refusal);
    auto entry = ctx.catalog().Find(id);
    if (!entry.ok()) return StatusError(entry.status());
    if (!*entry) return JsonError(http::status::not_found, "no mesh with id " + id);
    if ((*entry)->original.empty()) {
      return JsonError(http::status::not_found,
                       "mesh " + id + " has no original kept (ingested before originals were "
                                      "kept, or as a ready container)");
    }
    auto original = ctx.catalog().FindOriginal((*entry)->original);
    if (!original.ok()) return StatusError(original.status());
    if (!*original) {
      return JsonError(http::status::internal_server_error,
                       "the catalog lists no original " + (*entry)->original);
    }
    if (file.empty()) {
      proto::OriginalInfo info;
      info.set_mesh_id(id);
      info.set_digest((*original)->digest);
      info.set_main((*original)->main);
      info.set_format((*original)->format);
      info.set_bytes((*original)->bytes);
      for (const OriginalFile& f : (*original)->files) {
        auto* out = info.add_files();
        out->set_name(f.name);
        out->set_sha256(f.sha256);
        out->set_bytes(f.bytes);
      }
      return Message(req, info);
    }
    for (const OriginalFile& f : (*original)->files) {
      if (f.name != file) continue;
      auto bytes = ReadOriginalFile(ctx.catalog().store_dir(), f);
      if (!bytes.ok()) return JsonError(http::status::internal_server_error, bytes.status().message());
      Response out = Text(http::status::ok, std::move(*bytes), "application/octet-stream");
      out.set(http::field::content_disposition, "attachment");
      return out;
    }
    return JsonError(http::status::not_found,
                     "the original of mesh " + id + " has no file '" + std::string(file) + "'");
  }();
  // An upload is its owner's: no shared cache may keep it.
  r.set(http::field::cache_control, "private, no-store");
  return r;
}

}  // namespace meshwave::server
