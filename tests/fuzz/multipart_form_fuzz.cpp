// Fuzz target: an upload's multipart/form-data body (server/multipart_form.h,
// server/upload_files.h). The input is a Content-Type value, a line end,
// then the body: MultipartBoundary reads the first, ParseMultipartForm and
// FilesOfMultipart the second. Checked: every part's bytes lie inside the
// body, at most kMaxFormParts parts, and the files chosen are named as
// CheckFileSetName allows, each once, the main file among them.
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <string_view>

#include "fuzz_require_testonly.h"
#include "meshwave/file_set.h"
#include "multipart_form.h"
#include "upload_files.h"

using namespace meshwave;
using namespace meshwave::server;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const size_t line = input.find('\n');
  if (line == std::string_view::npos) return 0;
  const std::string_view content_type = input.substr(0, line);
  const std::string_view body = input.substr(line + 1);
  (void)IsMultipartFormData(content_type);
  const Result<std::string> boundary = MultipartBoundary(content_type);
  if (!boundary.ok()) return 0;
  const auto inside = [&](std::string_view part) {
    return part.empty() || (part.data() >= body.data() &&
                            part.data() + part.size() <= body.data() + body.size());
  };
  const auto parts = ParseMultipartForm(body, *boundary);
  if (parts.ok()) {
    fuzz::Require(!parts->empty() && parts->size() <= kMaxFormParts, "part count in bounds");
    for (const FormPart& p : *parts) {
      fuzz::Require(inside(p.bytes), "part bytes inside the body");
      fuzz::Require(!p.name.empty(), "every part has a name");
    }
  }
  const auto files = FilesOfMultipart(body, *boundary, std::nullopt);
  if (files.ok()) {
    fuzz::Require(parts.ok(), "files only from a well-formed body");
    std::set<std::string> names;
    bool main_found = false;
    for (const OriginalPart& p : files->parts) {
      fuzz::Require(CheckFileSetName(p.name).ok(), "file names are valid");
      fuzz::Require(names.insert(p.name).second, "file names are distinct");
      fuzz::Require(inside(p.bytes), "file bytes inside the body");
      main_found |= p.name == files->main;
    }
    fuzz::Require(main_found && IsMeshFileName(files->main), "the main file is a mesh part");
  }
  return 0;
}
