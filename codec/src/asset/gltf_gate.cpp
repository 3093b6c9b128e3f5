#include "asset/gltf_gate.h"

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace meshwave {
namespace {

using Json = nlohmann::json;

// Counts nesting and values while nlohmann-json's SAX parser (iterative,
// no document built) reads the text; stops at the first level or value
// past the limits or at the first syntax error, remembering where.
class DepthCheck final : public nlohmann::json_sax<Json> {
 public:
  DepthCheck(uint32_t max_depth, uint64_t max_values)
      : max_depth_(max_depth), max_values_(max_values) {}

  bool null() override { return Value(); }
  bool boolean(bool) override { return Value(); }
  bool number_integer(number_integer_t) override { return Value(); }
  bool number_unsigned(number_unsigned_t) override { return Value(); }
  bool number_float(number_float_t, const string_t&) override {
    return Value();
  }
  bool string(string_t&) override { return Value(); }
  bool binary(binary_t&) override { return Value(); }
  bool start_object(std::size_t) override { return Value() && Enter(); }
  bool key(string_t&) override { return true; }
  bool end_object() override { return Leave(); }
  bool start_array(std::size_t) override { return Value() && Enter(); }
  bool end_array() override { return Leave(); }
  bool parse_error(std::size_t position, const std::string&,
                   const nlohmann::detail::exception& e) override {
    error_position_ = position;
    error_ = e.what();
    return false;
  }

  bool too_deep() const { return too_deep_; }
  bool too_many() const { return too_many_; }
  const std::string& error() const { return error_; }
  size_t error_position() const { return error_position_; }

 private:
  bool Value() {
    if (++values_ > max_values_) {
      too_many_ = true;
      return false;
    }
    return true;
  }
  bool Enter() {
    if (++depth_ > max_depth_) {
      too_deep_ = true;
      return false;
    }
    return true;
  }
  bool Leave() {
    --depth_;
    return true;
  }

  uint32_t max_depth_;
  uint64_t max_values_;
  uint32_t depth_ = 0;
  uint64_t values_ = 0;
  bool too_deep_ = false;
  bool too_many_ = false;
  std::string error_;
  size_t error_position_ = 0;
};

// Values read the way tinygltf reads them (ParseIntegerProperty,
// ParseUnsignedProperty, ParseStringProperty).
std::optional<int> TinyInt(const Json& object, const char* key) {
  const auto it = object.find(key);
  if (it == object.end() || !it->is_number_integer()) return std::nullopt;
  return static_cast<int>(it->get<int64_t>());
}
std::optional<uint64_t> TinyUnsigned(const Json& object, const char* key) {
  const auto it = object.find(key);
  if (it == object.end() || !it->is_number_unsigned()) return std::nullopt;
  return it->get<uint64_t>();
}
std::optional<std::string> TinyString(const Json& object, const char* key) {
  const auto it = object.find(key);
  if (it == object.end() || !it->is_string()) return std::nullopt;
  return it->get<std::string>();
}

int HexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

class Gate {
 public:
  Gate(std::string_view json, bool is_glb, bool has_bin, size_t bin_size,
       FileSet& files, std::string_view main_name, const AssetLimits& limits)
      : json_(json),
        is_glb_(is_glb),
        has_bin_(has_bin),
        bin_size_(bin_size),
        files_(files),
        main_(main_name),
        limits_(limits) {}

  Result<GltfGateResult> Run() {
    if (json_.size() > limits_.max_json_bytes) {
      return Status(StatusCode::kUnsupported,
                    Prefix() + "the glTF JSON is " +
                        std::to_string(json_.size()) +
                        " bytes, more than the " +
                        std::to_string(limits_.max_json_bytes) + "-byte limit");
    }
    DepthCheck depth(limits_.max_json_depth, limits_.max_json_values);
    if (!Json::sax_parse(json_.begin(), json_.end(), &depth)) {
      if (depth.too_deep()) {
        return Status(StatusCode::kUnsupported,
                      Prefix() + "the glTF JSON nests deeper than " +
                          std::to_string(limits_.max_json_depth) + " levels");
      }
      if (depth.too_many()) {
        return Status(StatusCode::kUnsupported,
                      Prefix() + "the glTF JSON holds more than " +
                          std::to_string(limits_.max_json_values) + " values");
      }
      return ParseError(Prefix() + "invalid JSON at byte " +
                        std::to_string(depth.error_position()) + ": " +
                        depth.error());
    }
    const Json root = Json::parse(json_.begin(), json_.end(), nullptr,
                                  /*allow_exceptions=*/false);
    if (!root.is_object()) {
      return ParseError(Prefix() + "the glTF JSON is not an object");
    }
    MW_RETURN_IF_ERROR(CheckVersion(root));
    MW_RETURN_IF_ERROR(CheckRequiredExtensions(root));
    MW_RETURN_IF_ERROR(CheckBuffers(root));
    MW_RETURN_IF_ERROR(CheckBufferViews(root));
    return std::move(result_);
  }

 private:
  std::string Prefix() const { return std::string(main_) + ": "; }

  Status CheckVersion(const Json& root) const {
    const auto asset = root.find("asset");
    if (asset == root.end() || !asset->is_object()) {
      return ParseError(Prefix() + "no \"asset\" object: not a glTF file");
    }
    const std::optional<std::string> version = TinyString(*asset, "version");
    if (!version) return ParseError(Prefix() + "no asset.version");
    if (!version->starts_with("2.")) {
      return Status(StatusCode::kUnsupported,
                    Prefix() + "glTF version \"" + version->substr(0, 20) +
                        "\" (only glTF 2.0 is supported)");
    }
    return Status::Ok();
  }

  Status CheckRequiredExtensions(const Json& root) const {
    const auto required = root.find("extensionsRequired");
    if (required == root.end() || !required->is_array()) return Status::Ok();
    for (const Json& e : *required) {
      if (!e.is_string()) continue;
      const std::string& name = e.get_ref<const std::string&>();
      if (name == "KHR_draco_mesh_compression" ||
          name == "EXT_meshopt_compression" ||
          name == "KHR_meshopt_compression") {
        return Status(StatusCode::kUnsupported,
                      Prefix() + "the geometry is compressed with " + name +
                          ", which meshwave does not decode; export the glTF "
                          "without mesh compression (e.g. gltf-transform "
                          "copy, or Blender without Draco)");
      }
    }
    return Status::Ok();
  }

  Status CheckBuffers(const Json& root) {
    const auto buffers = root.find("buffers");
    if (buffers == root.end() || !buffers->is_array()) return Status::Ok();
    declared_.assign(buffers->size(), std::nullopt);
    for (size_t i = 0; i < buffers->size(); ++i) {
      const Json& b = (*buffers)[i];
      if (!b.is_object()) continue;  // tinygltf refuses it
      const std::optional<uint64_t> length = TinyUnsigned(b, "byteLength");
      declared_[i] = length;
      const std::string where = "buffer " + std::to_string(i);
      std::optional<std::string> uri = TinyString(b, "uri");
      if (uri && uri->empty() && is_glb_) uri.reset();
      if (!uri) {
        if (!is_glb_) continue;  // tinygltf: a .gltf buffer needs a uri
        if (i != 0) {
          return ParseError(Prefix() + where +
                            " has no uri; in a .glb only buffer 0 may stand "
                            "for the BIN chunk");
        }
        if (!has_bin_) {
          return ParseError(Prefix() +
                            "buffer 0 refers to the BIN chunk, and the .glb "
                            "has none");
        }
        if (length && *length > bin_size_) {
          return ParseError(Prefix() + "truncated: buffer 0 declares " +
                            std::to_string(*length) +
                            " bytes, the GLB's BIN chunk holds " +
                            std::to_string(bin_size_));
        }
        continue;
      }
      if (uri->starts_with("data:")) continue;  // decoded and sized by tinygltf
      MW_ASSIGN_OR_RETURN(const std::string name,
                          ResolveFileSetReference(main_, DecodeUriPath(*uri)));
      Result<std::string_view> bytes = files_.Read(name);
      if (!bytes.ok()) {
        return bytes.status().WithContext(std::string(main_) + ": " + where);
      }
      if (length && bytes->size() != *length) {
        return ParseError(Prefix() + where + " (" + name + ") declares " +
                          std::to_string(*length) + " bytes, the file has " +
                          std::to_string(bytes->size()) +
                          (bytes->size() < *length ? ": truncated" : ""));
      }
      result_.buffer_files[TinyGltfUrlDecode(*uri)] = *bytes;
    }
    return Status::Ok();
  }

  Status CheckBufferViews(const Json& root) const {
    const auto views = root.find("bufferViews");
    if (views == root.end() || !views->is_array()) return Status::Ok();
    for (size_t i = 0; i < views->size(); ++i) {
      const Json& v = (*views)[i];
      if (!v.is_object()) continue;
      const std::optional<int> buffer = TinyInt(v, "buffer");
      const std::optional<uint64_t> length = TinyUnsigned(v, "byteLength");
      if (!buffer || !length) continue;  // tinygltf refuses the view
      const uint64_t offset = TinyUnsigned(v, "byteOffset").value_or(0);
      if (*buffer < 0 || static_cast<size_t>(*buffer) >= declared_.size()) {
        return ParseError(Prefix() + "bufferView " + std::to_string(i) +
                          " refers to buffer " + std::to_string(*buffer) +
                          ", the file has " + std::to_string(declared_.size()));
      }
      const std::optional<uint64_t> size =
          declared_[static_cast<size_t>(*buffer)];
      if (!size) continue;  // tinygltf refuses the buffer
      if (offset > *size || *length > *size - offset) {
        return ParseError(Prefix() + "bufferView " + std::to_string(i) +
                          " spans bytes " + std::to_string(offset) + " to " +
                          std::to_string(offset + *length) + " of buffer " +
                          std::to_string(*buffer) + ", which has " +
                          std::to_string(*size));
      }
    }
    return Status::Ok();
  }

  std::string_view json_;
  bool is_glb_;
  bool has_bin_;
  size_t bin_size_;
  FileSet& files_;
  std::string_view main_;
  const AssetLimits& limits_;
  std::vector<std::optional<uint64_t>> declared_;  // byteLength per buffer
  GltfGateResult result_;
};

}  // namespace

std::string DecodeUriPath(std::string_view uri) {
  std::string out;
  out.reserve(uri.size());
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size()) {
      const int hi = HexValue(uri[i + 1]);
      const int lo = HexValue(uri[i + 2]);
      if (hi >= 0 && lo >= 0) {
        out += static_cast<char>(hi * 16 + lo);
        i += 2;
        continue;
      }
    }
    out += uri[i];
  }
  return out;
}

std::string TinyGltfUrlDecode(std::string_view uri) {
  // A copy of dlib::urldecode as tinygltf 2.7 has it, quirks included (a
  // '+' is a space, a bad hex digit is 0).
  auto from_hex = [](unsigned char c) -> unsigned char {
    if (c <= '9' && c >= '0') return static_cast<unsigned char>(c - '0');
    if (c <= 'f' && c >= 'a') return static_cast<unsigned char>(c - 'a' + 10);
    if (c <= 'F' && c >= 'A') return static_cast<unsigned char>(c - 'A' + 10);
    return 0;
  };
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '+') {
      out += ' ';
    } else if (uri[i] == '%' && uri.size() > i + 2) {
      const unsigned char hi = from_hex(static_cast<unsigned char>(uri[i + 1]));
      const unsigned char lo = from_hex(static_cast<unsigned char>(uri[i + 2]));
      out += static_cast<char>((hi << 4) | lo);
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

Result<GltfGateResult> CheckGltfDocument(std::string_view json, bool is_glb,
                                         bool has_bin, size_t bin_size,
                                         FileSet& files,
                                         std::string_view main_name,
                                         const AssetLimits& limits) {
  return Gate(json, is_glb, has_bin, bin_size, files, main_name, limits).Run();
}

}  // namespace meshwave
