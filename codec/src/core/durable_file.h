// Crash-safe file replacement, the one used by the codec's mesh writers, the
// server's store, the client's state files and the CLI: a file either exists
// whole under its final name (the old version or the new one) or not at all,
// and survives a power loss once the call returns.
#ifndef MESHWAVE_CORE_DURABLE_FILE_H_
#define MESHWAVE_CORE_DURABLE_FILE_H_

#include <filesystem>
#include <string_view>

#include "meshwave/status.h"

namespace meshwave {

// Prefix of the temporary files WriteFileDurably leaves behind when the
// process dies in the middle (the server's startup cleanup removes them).
inline constexpr std::string_view kDurableTempPrefix = ".tmp-";

// Writes `bytes` to a new temporary file in the directory of `path`, fsyncs
// it, renames it over `path` and fsyncs the directory. On failure the
// temporary file is removed and `path` is as it was; IoError naming the
// file and the system's reason ("cannot write DIR/.tmp-...: No space left
// on device").
Status WriteFileDurably(const std::filesystem::path& path, std::string_view bytes);

// fsync of a directory, so that renames and unlinks in it are durable.
Status SyncDirectory(const std::filesystem::path& dir);

}  // namespace meshwave

#endif  // MESHWAVE_CORE_DURABLE_FILE_H_
