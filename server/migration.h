// Versioned schema migrations of the catalog's two backends: the numbered
// SQL files of server/migrations/postgres/ and server/migrations/sqlite/
// (NNNN_name.sql), compiled into the binary by cmake/EmbedMigrations.cmake
// and applied in order when a catalog is opened. Both backends have the
// same tables; each file pair changes them alike.
#ifndef MESHWAVE_SERVER_MIGRATION_H_
#define MESHWAVE_SERVER_MIGRATION_H_

#include <string_view>
#include <vector>

namespace meshwave::server {

struct Migration {
  int version;            // the file's number
  std::string_view name;  // the file name
  std::string_view sql;
};

// Every migration in the repository, by version.
const std::vector<Migration>& PostgresMigrations();
const std::vector<Migration>& SqliteMigrations();

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_MIGRATION_H_
