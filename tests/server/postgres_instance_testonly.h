// A throwaway PostgreSQL server for tests, from Debian's packages: initdb
// in a fresh temporary directory, postgres on a free 127.0.0.1 port (as
// "nobody" when the test runs as root), stopped and removed on
// destruction, and killed with the test process if that dies.
#ifndef MESHWAVE_TESTS_SERVER_POSTGRES_INSTANCE_TESTONLY_H_
#define MESHWAVE_TESTS_SERVER_POSTGRES_INSTANCE_TESTONLY_H_

#include <libpq-fe.h>
#include <stdlib.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "process/child_process_testonly.h"

namespace meshwave::testing {

// The folder of initdb and postgres: $MESHWAVE_PG_BINDIR, else the newest
// /usr/lib/postgresql/<version>/bin that has them. Empty when none.
inline std::filesystem::path PostgresBinDir() {
  if (const char* dir = std::getenv("MESHWAVE_PG_BINDIR"); dir && *dir) return dir;
  std::filesystem::path best;
  int best_version = -1;
  std::error_code ec;
  for (const auto& d : std::filesystem::directory_iterator("/usr/lib/postgresql", ec)) {
    const auto bin = d.path() / "bin";
    if (!std::filesystem::exists(bin / "initdb") || !std::filesystem::exists(bin / "postgres")) {
      continue;
    }
    const int version = std::atoi(d.path().filename().c_str());
    if (version > best_version) {
      best_version = version;
      best = bin;
    }
  }
  return best;
}

// Why PostgreSQL tests cannot run here, or empty when they can. In CI
// (CI set) the caller should fail rather than skip: CI installs PostgreSQL
// (deploy/install-deps.sh), so a missing server is a broken setup.
inline std::string PostgresUnavailableReason() {
  if (PostgresBinDir().empty()) {
    return "PostgreSQL server binaries not found (Debian: apt-get install postgresql; or set "
           "MESHWAVE_PG_BINDIR)";
  }
  return "";
}

class PostgresInstance {
 public:
  PostgresInstance() {
    const auto bin = PostgresBinDir();
    if (bin.empty()) {
      error_ = PostgresUnavailableReason();
      return;
    }
    std::string tmpl = (std::filesystem::temp_directory_path() / "meshwave_pg_XXXXXX").string();
    if (::mkdtemp(tmpl.data()) == nullptr) {
      error_ = "cannot create a temporary directory";
      return;
    }
    dir_ = tmpl;
    const auto account = UnprivilegedAccount();
    if (account && ::chown(dir_.c_str(), account->uid, account->gid) != 0) {
      error_ = "cannot give " + dir_.string() + " to nobody";
      return;
    }
    const auto log = dir_ / "postgres.log";
    const int init = WaitChild(
        SpawnChild({(bin / "initdb").string(), "-D", (dir_ / "data").string(), "-U", "meshwave",
                    "-A", "trust", "-E", "UTF8", "--locale=C", "--no-sync", "--no-instructions"},
                   log, account),
        std::chrono::seconds(120));
    if (init != 0) {
      error_ = "initdb failed (" + std::to_string(init) + "): " + Log();
      return;
    }
    // A port can be taken between FreeLoopbackPort and the bind: retry.
    for (int attempt = 0; attempt < 5 && port_ == 0; ++attempt) {
      const uint16_t port = FreeLoopbackPort();
      // fsync off and no synchronous commit: a test database need not
      // survive a power loss, and it is several times faster.
      pid_ = SpawnChild({(bin / "postgres").string(), "-D", (dir_ / "data").string(), "-p",
                         std::to_string(port), "-k", dir_.string(), "-c",
                         "listen_addresses=127.0.0.1", "-c", "fsync=off", "-c",
                         "synchronous_commit=off", "-c", "full_page_writes=off", "-c",
                         "max_connections=40", "-c", "shared_buffers=16MB"},
                        log, account);
      if (WaitReady(port)) port_ = port;
    }
    if (port_ == 0) error_ = "postgres did not start: " + Log();
  }

  ~PostgresInstance() {
    // SIGINT: fast shutdown (disconnects clients, no checkpoint wait).
    if (pid_ > 0) StopChild(pid_, SIGINT, std::chrono::seconds(10));
    std::error_code ec;
    if (!dir_.empty()) std::filesystem::remove_all(dir_, ec);
  }
  PostgresInstance(const PostgresInstance&) = delete;
  PostgresInstance& operator=(const PostgresInstance&) = delete;

  bool ok() const { return port_ != 0; }
  const std::string& error() const { return error_; }
  uint16_t port() const { return port_; }
  pid_t pid() const { return pid_; }
  std::string Uri(const std::string& database = "postgres") const {
    return "postgres://meshwave@127.0.0.1:" + std::to_string(port_) + "/" + database;
  }
  // Runs SQL as the superuser; empty on success, else the error.
  std::string Exec(const std::string& sql, const std::string& database = "postgres") const {
    PGconn* c = PQconnectdb(Uri(database).c_str());
    std::string err;
    if (PQstatus(c) != CONNECTION_OK) {
      err = PQerrorMessage(c);
    } else {
      PGresult* r = PQexec(c, sql.c_str());
      const auto st = PQresultStatus(r);
      if (st != PGRES_COMMAND_OK && st != PGRES_TUPLES_OK) err = PQresultErrorMessage(r);
      PQclear(r);
    }
    PQfinish(c);
    return err;
  }
  std::string Log() const {
    std::ifstream in(dir_ / "postgres.log");
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }

 private:
  bool WaitReady(uint16_t port) {
    const std::string conninfo =
        "host=127.0.0.1 port=" + std::to_string(port) + " user=meshwave dbname=postgres";
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (std::chrono::steady_clock::now() < end) {
      if (PQping(conninfo.c_str()) == PQPING_OK) return true;
      if (!ProcessRuns(pid_)) {  // exited: port taken?
        WaitChild(pid_, std::chrono::seconds(1));
        pid_ = -1;
        return false;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    StopChild(pid_, SIGKILL, std::chrono::seconds(5));
    pid_ = -1;
    return false;
  }

  std::filesystem::path dir_;
  pid_t pid_ = -1;
  uint16_t port_ = 0;
  std::string error_;
};

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_SERVER_POSTGRES_INSTANCE_TESTONLY_H_
