#include "asset/gltf_loader.h"

#include <cstdint>
#include <exception>
#include <limits>
#include <new>

#include "asset/glb_container.h"
#include "asset/gltf_gate.h"

namespace meshwave {
namespace {

// What the callbacks see (tinygltf passes it back as user data).
struct CallbackContext {
  const GltfGateResult* gate;
  const tinygltf::Model* model;  // being filled: buffers are there first
  uint64_t image_bytes_left;
  std::string error;  // why the image callback refused
};

const std::string_view* FindBuffer(const CallbackContext& c,
                                   const std::string& path) {
  std::string_view name = path;
  while (name.starts_with("./")) name.remove_prefix(2);
  const auto it = c.gate->buffer_files.find(name);
  return it == c.gate->buffer_files.end() ? nullptr : &it->second;
}

bool FileExists(const std::string& path, void* user) {
  return FindBuffer(*static_cast<CallbackContext*>(user), path) != nullptr;
}

std::string ExpandFilePath(const std::string& path, void*) { return path; }

bool ReadWholeFile(std::vector<unsigned char>* out, std::string* err,
                   const std::string& path, void* user) {
  const std::string_view* bytes =
      FindBuffer(*static_cast<CallbackContext*>(user), path);
  if (bytes == nullptr) {
    if (err) *err += "not a buffer of this glTF";
    return false;
  }
  out->assign(bytes->begin(), bytes->end());
  return true;
}

bool WriteWholeFile(std::string* err, const std::string&,
                    const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing is not allowed";
  return false;
}

// Keeps an image's encoded bytes (from a data URI or a bufferView) for our
// decoders. tinygltf hands over a pointer into a buffer computed without a
// bounds check; the gate has checked every bufferView against its buffer,
// and this checks the view once more before reading.
bool KeepImageBytes(tinygltf::Image* image, const int index, std::string* err,
                    std::string*, int, int, const unsigned char* bytes,
                    int size, void* user) {
  auto& c = *static_cast<CallbackContext*>(user);
  auto refuse = [&](const std::string& why) {
    c.error = "image " + std::to_string(index) + ": " + why;
    if (err) *err += c.error + "\n";
    return false;
  };
  if (size <= 0) return refuse("no bytes");
  if (image->bufferView >= 0) {
    const auto& views = c.model->bufferViews;
    if (static_cast<size_t>(image->bufferView) >= views.size()) {
      return refuse("bufferView out of range");
    }
    const tinygltf::BufferView& v =
        views[static_cast<size_t>(image->bufferView)];
    if (v.buffer < 0 ||
        static_cast<size_t>(v.buffer) >= c.model->buffers.size()) {
      return refuse("buffer out of range");
    }
    const auto& data = c.model->buffers[static_cast<size_t>(v.buffer)].data;
    if (v.byteOffset > data.size() ||
        v.byteLength > data.size() - v.byteOffset ||
        bytes != data.data() + v.byteOffset ||
        static_cast<size_t>(size) != v.byteLength) {
      return refuse("bufferView outside its buffer");
    }
  }
  if (static_cast<uint64_t>(size) > c.image_bytes_left) {
    return refuse("the encoded images take more than the file-byte limit");
  }
  c.image_bytes_left -= static_cast<uint64_t>(size);
  image->image.assign(bytes, bytes + size);
  return true;
}

// tinygltf's messages end lines with '\n'; one line each for ours.
std::string Tidy(const std::string& text) {
  std::string out;
  for (char ch : text) {
    if (ch == '\n') {
      if (!out.empty() && out.back() != ' ') out += "; ";
    } else {
      out += ch;
    }
  }
  while (!out.empty() && (out.back() == ' ' || out.back() == ';'))
    out.pop_back();
  return out;
}

}  // namespace

Result<tinygltf::Model> LoadGltfModel(std::string_view bytes, FileSet& files,
                                      std::string_view main_name,
                                      const AssetLimits& limits,
                                      std::vector<std::string>* warnings) {
  const bool is_glb = LooksLikeGlb(bytes);
  GlbChunks chunks;
  if (is_glb) {
    MW_ASSIGN_OR_RETURN(chunks, ParseGlb(bytes, main_name));
    if (bytes.size() > std::numeric_limits<unsigned int>::max()) {
      return Status(StatusCode::kUnsupported,
                    std::string(main_name) + ": a .glb of 4 GiB or more");
    }
  } else {
    chunks.json = bytes;
    if (bytes.size() > std::numeric_limits<unsigned int>::max()) {
      return Status(StatusCode::kUnsupported,
                    std::string(main_name) + ": a .gltf of 4 GiB or more");
    }
  }
  Result<GltfGateResult> checked = Status(StatusCode::kInternal, "unset");
  try {
    checked = CheckGltfDocument(chunks.json, is_glb, chunks.has_bin,
                                chunks.bin.size(), files, main_name, limits);
  } catch (const std::bad_alloc&) {
    return Status(StatusCode::kUnsupported,
                  std::string(main_name) + ": out of memory reading the glTF");
  }
  MW_ASSIGN_OR_RETURN(const GltfGateResult gate, std::move(checked));

  tinygltf::Model model;
  CallbackContext context{&gate, &model, limits.max_file_bytes, {}};
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks(tinygltf::FsCallbacks{
      &FileExists, &ExpandFilePath, &ReadWholeFile, &WriteWholeFile, &context});
  loader.SetImageLoader(&KeepImageBytes, &context);
  std::string err;
  std::string warn;
  bool ok = false;
  try {
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    const auto size = static_cast<unsigned int>(bytes.size());
    ok = is_glb
             ? loader.LoadBinaryFromMemory(&model, &err, &warn, data, size, "")
             : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(),
                                          size, "");
  } catch (const std::bad_alloc&) {
    return Status(StatusCode::kUnsupported,
                  std::string(main_name) + ": out of memory reading the glTF");
  } catch (const std::exception& e) {
    return ParseError(std::string(main_name) + ": malformed glTF (" + e.what() +
                      ")");
  }
  if (!ok) {
    return ParseError(
        std::string(main_name) + ": " +
        (err.empty() ? std::string("malformed glTF") : Tidy(err)));
  }
  if (!warn.empty() && warnings != nullptr) {
    warnings->push_back(std::string(main_name) + ": " + Tidy(warn));
  }
  return model;
}

}  // namespace meshwave
