// Runs a test against each catalog backend: SQLite in a temporary
// directory, and PostgreSQL on a throwaway server of its own
// (postgres_instance_testonly.h) with a temporary container store.
#ifndef MESHWAVE_TESTS_SERVER_CATALOG_BACKENDS_TESTONLY_H_
#define MESHWAVE_TESTS_SERVER_CATALOG_BACKENDS_TESTONLY_H_

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <string>

#include "catalog.h"
#include "e2e/cli_runner.h"
#include "server/postgres_instance_testonly.h"

namespace meshwave::testing {

enum class CatalogBackend { kSqlite, kPostgres };

inline std::string CatalogBackendName(const ::testing::TestParamInfo<CatalogBackend>& info) {
  return info.param == CatalogBackend::kSqlite ? "Sqlite" : "Postgres";
}

class CatalogBackendTest : public ::testing::TestWithParam<CatalogBackend> {
 protected:
  void SetUp() override {
    if (GetParam() != CatalogBackend::kPostgres) return;
    if (const std::string why = PostgresUnavailableReason(); !why.empty()) {
      // CI installs PostgreSQL: there a missing server is a failure.
      if (std::getenv("CI") != nullptr) FAIL() << why << " (CI must run the PostgreSQL tests)";
      GTEST_SKIP() << why;
    }
    pg_ = std::make_unique<PostgresInstance>();
    ASSERT_TRUE(pg_->ok()) << pg_->error();
  }

  // "postgres://..." or the SQLite directory.
  std::string location() const {
    return pg_ ? pg_->Uri() : (tmp_ / "catalog").string();
  }
  std::filesystem::path store() const {
    return pg_ ? tmp_ / "store" : std::filesystem::path();
  }
  // A new handle on this test's catalog: another connection each time, as
  // another replica or the ingest command would have.
  std::unique_ptr<server::Catalog> OpenCatalog() {
    auto catalog = server::Catalog::Open(location(), store());
    EXPECT_TRUE(catalog.ok()) << catalog.status().ToString();
    return catalog.ok() ? std::move(*catalog) : nullptr;
  }

  TempDir tmp_;
  std::unique_ptr<PostgresInstance> pg_;
};

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_SERVER_CATALOG_BACKENDS_TESTONLY_H_
