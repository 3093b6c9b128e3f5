// An upload's ingest in a worker process (worker_process.h): the server
// runs `meshwave-server ingest-upload` with the upload on its standard
// input; the worker ingests it into the catalog and prints its outcome as
// lines of text, which the server reads back.
#ifndef MESHWAVE_SERVER_UPLOAD_WORKER_H_
#define MESHWAVE_SERVER_UPLOAD_WORKER_H_

#include <filesystem>
#include <string>
#include <string_view>

#include "encode_settings.h"
#include "ingest.h"
#include "meshwave/status.h"
#include "worker_process.h"

namespace meshwave::server {

struct UploadOutcome {
  std::string id;
  bool already_present = false;
  bool remeshed = false;
  double fidelity_db = 0;
};

// "id ID", "already_present 0|1", "remeshed 0|1", "fidelity_db X", one a
// line; or "error CODE MESSAGE" (CODE: the StatusCode's number).
std::string FormatUploadOutcome(const Result<IngestResult>& result);
// Reads it back: the outcome, or the worker's error with its code.
// kInternal when the text is neither.
Result<UploadOutcome> ParseUploadOutcome(std::string_view text);

// Ingests an upload's body: with `boundary` empty, the one file `source`;
// else a multipart/form-data body (upload_files.h) whose main file is
// `source`, all its parts kept as the original.
Result<IngestResult> IngestUpload(Catalog& catalog, std::string_view body, const std::string& name,
                                  const std::string& source, const std::string& boundary,
                                  const EncodeChoices& choices);

// Runs the worker on `bytes` (IngestUpload's body, `source` and `boundary`
// for the upload named `name`) against the catalog at `catalog` (+
// `store`), and returns its outcome; a worker that dies (out of memory, a
// signal) is a kInternal error saying how it ended.
Result<UploadOutcome> IngestInWorker(const std::string& catalog,
                                     const std::filesystem::path& store, std::string_view bytes,
                                     const std::string& name, const std::string& source,
                                     const std::string& boundary, const EncodeChoices& choices,
                                     const WorkerOptions& options);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_UPLOAD_WORKER_H_
