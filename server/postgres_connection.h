// One libpq connection to PostgreSQL with text-format parameters and
// results, errors as Status values carrying the server's message and
// SQLSTATE. Not thread-safe: the owner serializes calls.
#ifndef MESHWAVE_SERVER_POSTGRES_CONNECTION_H_
#define MESHWAVE_SERVER_POSTGRES_CONNECTION_H_

#include <libpq-fe.h>

#include <memory>
#include <string>
#include <vector>

#include "meshwave/status.h"

namespace meshwave::server {

// A query's rows (text format), freed on destruction.
class PgResult {
 public:
  explicit PgResult(PGresult* r) : r_(r, &PQclear) {}
  int rows() const { return PQntuples(r_.get()); }
  std::string Text(int row, int column) const {
    return std::string(PQgetvalue(r_.get(), row, column),
                       static_cast<size_t>(PQgetlength(r_.get(), row, column)));
  }
  // Rows a command touched (DELETE, INSERT, UPDATE).
  uint64_t affected() const;
  PGresult* get() const { return r_.get(); }

 private:
  std::unique_ptr<PGresult, void (*)(PGresult*)> r_;
};

struct PgError {
  std::string sqlstate;  // e.g. "23505" (unique_violation); empty when none
};

class PostgresConnection {
 public:
  // Connects to a postgres:// URI (libpq syntax; PGPASSWORD and the other
  // PG* environment variables apply). A 10 s connect timeout unless the
  // URI sets connect_timeout. IoError with libpq's message.
  static Result<std::unique_ptr<PostgresConnection>> Connect(const std::string& uri);
  ~PostgresConnection();
  PostgresConnection(const PostgresConnection&) = delete;
  PostgresConnection& operator=(const PostgresConnection&) = delete;

  // One statement with $1.. parameters as text. `error`, when given,
  // receives the SQLSTATE of a failure.
  Result<PgResult> Exec(const std::string& sql, const std::vector<std::string>& params = {},
                        PgError* error = nullptr);
  // Several statements without parameters (the simple query protocol),
  // e.g. a migration file.
  Status ExecScript(const std::string& sql);

  // True when the connection to the server is lost.
  bool broken() const { return PQstatus(conn_) != CONNECTION_OK; }
  // Reconnects with the same parameters.
  Status Reset();

 private:
  explicit PostgresConnection(PGconn* conn) : conn_(conn) {}
  Status Error(const std::string& what, PGresult* r, PgError* error) const;

  PGconn* conn_;
};

// "postgres://user@host:port/dbname" for logs: the URI without password
// or options. The URI itself when libpq cannot parse it.
std::string DescribePostgresUri(const std::string& uri);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_POSTGRES_CONNECTION_H_
