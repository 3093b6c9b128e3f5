#include "postgres_migrations.h"

#include <spdlog/spdlog.h>

#include <string>

namespace meshwave::server {
namespace {

// pg_advisory_xact_lock key, shared by every replica (the ingest lock of
// postgres_catalog.cpp is the one before).
constexpr char kMigrationLockKey[] = "4270537002";

constexpr char kCreateVersionTable[] = R"sql(
CREATE TABLE IF NOT EXISTS schema_version (
  version    integer     PRIMARY KEY,
  name       text        NOT NULL,
  applied_at timestamptz NOT NULL DEFAULT now()
))sql";

Status Apply(PostgresConnection& conn, const std::vector<Migration>& migrations) {
  MW_RETURN_IF_ERROR(conn.Exec("SELECT pg_advisory_xact_lock($1::bigint)", {kMigrationLockKey}).status());
  MW_RETURN_IF_ERROR(conn.Exec(kCreateVersionTable).status());
  MW_ASSIGN_OR_RETURN(const int current, SchemaVersion(conn));
  const int newest = migrations.empty() ? 0 : migrations.back().version;
  if (current > newest) {
    return Status(StatusCode::kUnsupported,
                  "postgres: the catalog's schema is at version " + std::to_string(current) +
                      ", newer than this server knows (" + std::to_string(newest) +
                      "): upgrade meshwave-server");
  }
  for (const Migration& m : migrations) {
    if (m.version <= current) continue;
    spdlog::info("catalog: applying migration {}", m.name);
    MW_RETURN_IF_ERROR(conn.ExecScript(std::string(m.sql)).WithContext(std::string(m.name)));
    MW_RETURN_IF_ERROR(conn.Exec("INSERT INTO schema_version (version, name) VALUES ($1, $2)",
                                 {std::to_string(m.version), std::string(m.name)})
                           .status());
  }
  return Status::Ok();
}

}  // namespace

Result<int> SchemaVersion(PostgresConnection& conn) {
  MW_ASSIGN_OR_RETURN(
      PgResult r, conn.Exec("SELECT coalesce(max(version), 0) FROM schema_version"));
  return std::stoi(r.Text(0, 0));
}

Status MigrateSchema(PostgresConnection& conn, const std::vector<Migration>& migrations) {
  for (size_t i = 0; i < migrations.size(); ++i) {
    if (migrations[i].version != static_cast<int>(i) + 1) {
      return Status(StatusCode::kInternal, "postgres: migration " +
                                               std::string(migrations[i].name) +
                                               " is out of sequence (expected number " +
                                               std::to_string(i + 1) + ")");
    }
  }
  MW_RETURN_IF_ERROR(conn.ExecScript("BEGIN"));
  Status s = Apply(conn, migrations);
  if (!s.ok()) {
    (void)conn.ExecScript("ROLLBACK");
    return s;
  }
  return conn.ExecScript("COMMIT");
}

}  // namespace meshwave::server
