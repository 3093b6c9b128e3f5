// A FileSet that passes reads through to another and notes the names of
// the files it handed out: run an asset reader over it to learn which
// sidecar files (.bin, .mtl, images) a mesh file is made of.
#ifndef MESHWAVE_SERVER_RECORDING_FILE_SET_H_
#define MESHWAVE_SERVER_RECORDING_FILE_SET_H_

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

#include "meshwave/file_set.h"

namespace meshwave::server {

class RecordingFileSet final : public FileSet {
 public:
  explicit RecordingFileSet(FileSet& files) : files_(files) {}

  Result<std::string_view> Read(std::string_view name) override {
    Result<std::string_view> bytes = files_.Read(name);
    if (bytes.ok() && std::find(read_.begin(), read_.end(), name) == read_.end()) {
      read_.emplace_back(name);
    }
    return bytes;
  }
  bool Contains(std::string_view name) const override { return files_.Contains(name); }
  std::string Describe() const override { return files_.Describe(); }

  // The files read, each once, in the order first read.
  const std::vector<std::string>& read() const { return read_; }

 private:
  FileSet& files_;
  std::vector<std::string> read_;
};

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_RECORDING_FILE_SET_H_
