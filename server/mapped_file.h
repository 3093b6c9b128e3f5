// A read-only memory map of a whole file. Responses hold it by shared_ptr,
// so a container deleted or evicted mid-response stays readable until the
// last byte is sent (unlinking a mapped file is safe on POSIX).
#ifndef MESHWAVE_SERVER_MAPPED_FILE_H_
#define MESHWAVE_SERVER_MAPPED_FILE_H_

#include <filesystem>
#include <memory>
#include <string_view>

#include "meshwave/status.h"

namespace meshwave::server {

class MappedFile {
 public:
  static Result<std::shared_ptr<const MappedFile>> Open(const std::filesystem::path& path);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  std::string_view bytes() const { return {data_, size_}; }

 private:
  MappedFile(const char* data, size_t size) : data_(data), size_(size) {}
  const char* data_;
  size_t size_;
};

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_MAPPED_FILE_H_
