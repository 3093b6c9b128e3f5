#include "catalog.h"

#include "postgres_catalog.h"
#include "sqlite_catalog.h"

namespace meshwave::server {

bool Catalog::IsPostgresUri(const std::string& location) {
  return location.starts_with("postgres://") || location.starts_with("postgresql://");
}

Result<std::unique_ptr<Catalog>> Catalog::Open(const std::string& location,
                                               const std::filesystem::path& store) {
  if (location.empty()) return InvalidArgument("catalog: no location given");
  if (IsPostgresUri(location)) {
    if (store.empty()) {
      return InvalidArgument(
          "catalog: a PostgreSQL catalog needs a container store directory (--store DIR)");
    }
    MW_ASSIGN_OR_RETURN(auto catalog, PostgresCatalog::Open(location, store));
    return std::unique_ptr<Catalog>(std::move(catalog));
  }
  if (!store.empty()) {
    return InvalidArgument(
        "catalog: --store is only for a postgres:// catalog; an SQLite catalog keeps its "
        "containers in DIR/containers/");
  }
  MW_ASSIGN_OR_RETURN(auto catalog, SqliteCatalog::Open(location));
  return std::unique_ptr<Catalog>(std::move(catalog));
}

}  // namespace meshwave::server
