// Versioned schema migrations of the PostgreSQL catalog: the numbered SQL
// files of server/migrations/postgres/ (NNNN_name.sql), compiled into the
// binary, applied in order at startup. schema_version records each one.
#ifndef MESHWAVE_SERVER_POSTGRES_MIGRATIONS_H_
#define MESHWAVE_SERVER_POSTGRES_MIGRATIONS_H_

#include <string_view>
#include <vector>

#include "meshwave/status.h"
#include "migration.h"
#include "postgres_connection.h"

namespace meshwave::server {

// Brings the database to the newest version of `migrations` (versions
// must be 1, 2, 3, ...): in one transaction holding an advisory lock, so
// replicas starting together apply each migration once. kUnsupported when
// the database is newer than this binary; nothing changes on any error.
Status MigrateSchema(PostgresConnection& conn, const std::vector<Migration>& migrations);

// The version recorded in schema_version (0 for an empty database).
Result<int> SchemaVersion(PostgresConnection& conn);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_POSTGRES_MIGRATIONS_H_
