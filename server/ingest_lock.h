// An exclusive flock on DIR/ingest.lock, held while a container is written
// and its row inserted, and while orphans are removed: processes and
// threads sharing a catalog directory then never see each other's half
// done ingest as an orphan.
#ifndef MESHWAVE_SERVER_INGEST_LOCK_H_
#define MESHWAVE_SERVER_INGEST_LOCK_H_

#include <filesystem>

#include "meshwave/status.h"

namespace meshwave::server {

class IngestLock {
 public:
  // Blocks until the lock is held; check ok().
  explicit IngestLock(const std::filesystem::path& catalog_dir);
  ~IngestLock();
  IngestLock(const IngestLock&) = delete;
  IngestLock& operator=(const IngestLock&) = delete;
  const Status& status() const { return status_; }

 private:
  int fd_ = -1;
  Status status_;
};

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_INGEST_LOCK_H_
