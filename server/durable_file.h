// Crash-safe file creation: a file either exists whole under its final name
// or not at all, and survives a power loss once the call returns.
#ifndef MESHWAVE_SERVER_DURABLE_FILE_H_
#define MESHWAVE_SERVER_DURABLE_FILE_H_

#include <filesystem>
#include <string_view>

#include "meshwave/status.h"

namespace meshwave::server {

// Prefix of the temporary files WriteFileDurably leaves behind when the
// process dies in the middle; startup cleanup removes them.
inline constexpr std::string_view kTempPrefix = ".tmp-";

// Writes `bytes` to a temporary file in the directory of `path`, fsyncs it,
// renames it to `path` and fsyncs the directory. IoError naming the path.
Status WriteFileDurably(const std::filesystem::path& path, std::string_view bytes);

// fsync of a directory, so that renames and unlinks in it are durable.
Status SyncDirectory(const std::filesystem::path& dir);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_DURABLE_FILE_H_
