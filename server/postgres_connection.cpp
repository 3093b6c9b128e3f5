#include "postgres_connection.h"

#include <spdlog/spdlog.h>

#include <charconv>
#include <cstring>

namespace meshwave::server {
namespace {

std::string Trimmed(const char* message) {
  std::string m = message ? message : "";
  while (!m.empty() && (m.back() == '\n' || m.back() == ' ')) m.pop_back();
  return m;
}

}  // namespace

uint64_t PgResult::affected() const {
  const char* s = PQcmdTuples(r_.get());
  uint64_t n = 0;
  std::from_chars(s, s + std::strlen(s), n);
  return n;
}

Result<std::unique_ptr<PostgresConnection>> PostgresConnection::Connect(const std::string& uri) {
  // Keywords are applied in order and the URI (expanded from "dbname")
  // comes last, so its own connect_timeout wins over the default.
  const char* keywords[] = {"connect_timeout", "application_name", "dbname", nullptr};
  const char* values[] = {"10", "meshwave-server", uri.c_str(), nullptr};
  PGconn* conn = PQconnectdbParams(keywords, values, /*expand_dbname=*/1);
  if (conn == nullptr) return IoError("postgres: out of memory");
  if (PQstatus(conn) != CONNECTION_OK) {
    Status s = IoError("postgres: cannot connect to " + DescribePostgresUri(uri) + ": " +
                       Trimmed(PQerrorMessage(conn)));
    PQfinish(conn);
    return s;
  }
  // NOTICEs ("relation already exists, skipping") are for debugging only.
  PQsetNoticeProcessor(
      conn, [](void*, const char* message) { spdlog::debug("postgres: {}", Trimmed(message)); },
      nullptr);
  return std::unique_ptr<PostgresConnection>(new PostgresConnection(conn));
}

PostgresConnection::~PostgresConnection() { PQfinish(conn_); }

Status PostgresConnection::Error(const std::string& what, PGresult* r, PgError* error) const {
  const char* state = r ? PQresultErrorField(r, PG_DIAG_SQLSTATE) : nullptr;
  if (error) error->sqlstate = state ? state : "";
  const char* message = r ? PQresultErrorMessage(r) : nullptr;
  return IoError("postgres: " + what + ": " +
                 Trimmed(message && *message ? message : PQerrorMessage(conn_)));
}

Result<PgResult> PostgresConnection::Exec(const std::string& sql,
                                          const std::vector<std::string>& params,
                                          PgError* error) {
  std::vector<const char*> values;
  values.reserve(params.size());
  for (const auto& p : params) values.push_back(p.c_str());
  PgResult result(PQexecParams(conn_, sql.c_str(), static_cast<int>(values.size()), nullptr,
                               values.data(), nullptr, nullptr, /*resultFormat=*/0));
  const ExecStatusType status = PQresultStatus(result.get());
  if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK) {
    return Error(sql.substr(0, sql.find(' ')), result.get(), error);
  }
  return result;
}

Status PostgresConnection::ExecScript(const std::string& sql) {
  // PQexec runs every statement of the string and returns the last result;
  // it stops at the first failing one, whose result that is.
  PgResult result(PQexec(conn_, sql.c_str()));
  const ExecStatusType status = PQresultStatus(result.get());
  if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK) {
    return Error("script", result.get(), nullptr);
  }
  return Status::Ok();
}

Status PostgresConnection::Reset() {
  PQreset(conn_);
  if (PQstatus(conn_) != CONNECTION_OK) {
    return IoError("postgres: cannot reconnect: " + Trimmed(PQerrorMessage(conn_)));
  }
  return Status::Ok();
}

std::string DescribePostgresUri(const std::string& uri) {
  char* error = nullptr;
  PQconninfoOption* options = PQconninfoParse(uri.c_str(), &error);
  if (options == nullptr) {
    PQfreemem(error);
    return uri;
  }
  std::string user, host, port, dbname;
  for (PQconninfoOption* o = options; o->keyword; ++o) {
    if (!o->val) continue;
    const std::string k = o->keyword;
    if (k == "user") user = o->val;
    if (k == "host") host = o->val;
    if (k == "port") port = o->val;
    if (k == "dbname") dbname = o->val;
  }
  PQconninfoFree(options);
  std::string out = "postgres://";
  if (!user.empty()) out += user + "@";
  out += host;
  if (!port.empty()) out += ":" + port;
  return out + "/" + dbname;
}

}  // namespace meshwave::server
