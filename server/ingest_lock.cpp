#include "ingest_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

namespace meshwave::server {

IngestLock::IngestLock(const std::filesystem::path& catalog_dir) {
  const std::filesystem::path path = catalog_dir / "ingest.lock";
  // Each lock opens its own descriptor: flock locks belong to the open file
  // description, so two threads of one process exclude each other too.
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    status_ = IoError("cannot open " + path.string() + ": " + std::strerror(errno));
    return;
  }
  while (::flock(fd_, LOCK_EX) != 0) {
    if (errno == EINTR) continue;
    status_ = IoError("cannot lock " + path.string() + ": " + std::strerror(errno));
    return;
  }
}

IngestLock::~IngestLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the lock
}

}  // namespace meshwave::server
