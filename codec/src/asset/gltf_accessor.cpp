#include "asset/gltf_accessor.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <optional>

#include "core/byte_reader.h"

namespace meshwave {
namespace {

static_assert(std::endian::native == std::endian::little,
              "glTF buffers are little-endian; this reader loads them as is");

int ComponentSize(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

const char* ComponentName(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_INT:
      return "INT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return "FLOAT";
    default:
      return "an unknown component type";
  }
}

// Components of SCALAR, VECn; 0 for matrices and anything else.
int VectorComponents(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
      return 4;
    default:
      return 0;
  }
}

template <class T>
T LoadLittle(const unsigned char* p) {
  T value;
  std::memcpy(&value, p, sizeof(T));
  return value;
}

double LoadComponent(const unsigned char* p, int component_type,
                     bool normalized) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const double v = LoadLittle<int8_t>(p);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const double v = LoadLittle<uint8_t>(p);
      return normalized ? v / 255.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const double v = LoadLittle<int16_t>(p);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const double v = LoadLittle<uint16_t>(p);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return LoadLittle<uint32_t>(p);
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return LoadLittle<float>(p);
    default:
      return 0.0;
  }
}

// A byte range of a buffer: bufferView `view_index` checked against its
// buffer. Views of the buffer's data, never past its end.
struct ViewBytes {
  const unsigned char* data = nullptr;
  size_t size = 0;
  size_t stride = 0;  // 0: tightly packed
};

class AccessorReader {
 public:
  AccessorReader(const tinygltf::Model& model, const std::string& context,
                 const AccessorSpec& spec, int index)
      : model_(model), context_(context), spec_(spec), index_(index) {}

  Result<AccessorValues> Read() {
    if (index_ < 0 || static_cast<size_t>(index_) >= model_.accessors.size()) {
      return Error("refers to accessor " + std::to_string(index_) +
                   ", the file has " + std::to_string(model_.accessors.size()));
    }
    const tinygltf::Accessor& a = model_.accessors[static_cast<size_t>(index_)];
    const int components = VectorComponents(a.type);
    if (components == 0 || (spec_.type_mask & TypeBit(components)) == 0) {
      return Error("has the wrong type (" + TypeName(a.type) + ")");
    }
    const int csize = ComponentSize(a.componentType);
    const uint32_t mask =
        a.normalized ? spec_.normalized_mask : spec_.plain_mask;
    if (csize == 0 || (mask & ComponentBit(a.componentType)) == 0) {
      return Error(std::string("has components of type ") +
                   (a.normalized ? "normalized " : "") +
                   ComponentName(a.componentType) + ", which " + spec_.what +
                   " may not have");
    }
    if (a.count == 0) return Error("has no elements (count 0)");
    if (a.count > spec_.max_count) {
      return Error("has " + std::to_string(a.count) +
                   " elements, more than the " +
                   std::to_string(spec_.max_count) + " allowed");
    }
    AccessorValues out;
    out.components = components;
    out.count = a.count;
    const size_t element = static_cast<size_t>(csize) * components;
    // count <= max_count keeps this far from overflow.
    out.values.assign(a.count * static_cast<size_t>(components), 0.0);
    if (a.bufferView >= 0) {
      MW_ASSIGN_OR_RETURN(const ViewBytes view, View(a.bufferView));
      const size_t stride = view.stride != 0 ? view.stride : element;
      if (stride < element) {
        return Error("has elements of " + std::to_string(element) +
                     " bytes but its bufferView's byteStride is " +
                     std::to_string(stride));
      }
      // The last element ends at byteOffset + (count - 1) * stride + element.
      const std::optional<size_t> span = CheckedMul(a.count - 1, stride);
      if (!span || a.byteOffset > view.size ||
          *span > view.size - a.byteOffset ||
          element > view.size - a.byteOffset - *span) {
        return Error("reaches past the end of bufferView " +
                     std::to_string(a.bufferView) + " (" +
                     std::to_string(a.count) + " elements of stride " +
                     std::to_string(stride) + " from byte " +
                     std::to_string(a.byteOffset) + " of " +
                     std::to_string(view.size) + "): a truncated buffer?");
      }
      for (size_t i = 0; i < a.count; ++i) {
        const unsigned char* p = view.data + a.byteOffset + i * stride;
        for (int c = 0; c < components; ++c) {
          out.values[i * components + c] =
              LoadComponent(p + c * csize, a.componentType, a.normalized);
        }
      }
    }
    if (a.sparse.isSparse) {
      MW_RETURN_IF_ERROR(ApplySparse(a, components, csize, element, out));
    }
    return out;
  }

 private:
  Status Error(const std::string& what) const {
    return ParseError(context_ + ": " + spec_.what + " (accessor " +
                      std::to_string(index_) + ") " + what);
  }

  static std::string TypeName(int type) {
    switch (type) {
      case TINYGLTF_TYPE_SCALAR:
        return "SCALAR";
      case TINYGLTF_TYPE_VEC2:
        return "VEC2";
      case TINYGLTF_TYPE_VEC3:
        return "VEC3";
      case TINYGLTF_TYPE_VEC4:
        return "VEC4";
      case TINYGLTF_TYPE_MAT2:
        return "MAT2";
      case TINYGLTF_TYPE_MAT3:
        return "MAT3";
      case TINYGLTF_TYPE_MAT4:
        return "MAT4";
      default:
        return "unknown";
    }
  }

  Result<ViewBytes> View(int view_index) const {
    if (view_index < 0 ||
        static_cast<size_t>(view_index) >= model_.bufferViews.size()) {
      return Error("refers to bufferView " + std::to_string(view_index) +
                   ", the file has " +
                   std::to_string(model_.bufferViews.size()));
    }
    const tinygltf::BufferView& v =
        model_.bufferViews[static_cast<size_t>(view_index)];
    if (v.buffer < 0 ||
        static_cast<size_t>(v.buffer) >= model_.buffers.size()) {
      return Error("uses bufferView " + std::to_string(view_index) +
                   ", which refers to buffer " + std::to_string(v.buffer) +
                   " (the file has " + std::to_string(model_.buffers.size()) +
                   ")");
    }
    const std::vector<unsigned char>& data =
        model_.buffers[static_cast<size_t>(v.buffer)].data;
    if (v.byteOffset > data.size() ||
        v.byteLength > data.size() - v.byteOffset) {
      return Error("uses bufferView " + std::to_string(view_index) +
                   ", bytes " + std::to_string(v.byteOffset) + " to " +
                   std::to_string(v.byteOffset + v.byteLength) + " of buffer " +
                   std::to_string(v.buffer) + ", which holds " +
                   std::to_string(data.size()) + ": a truncated buffer?");
    }
    return ViewBytes{data.data() + v.byteOffset, v.byteLength, v.byteStride};
  }

  Status ApplySparse(const tinygltf::Accessor& a, int components, int csize,
                     size_t element, AccessorValues& out) const {
    const auto& s = a.sparse;
    if (s.count < 1 || static_cast<size_t>(s.count) > a.count) {
      return Error("has a sparse count of " + std::to_string(s.count) +
                   " (1 to " + std::to_string(a.count) + " allowed)");
    }
    const size_t n = static_cast<size_t>(s.count);
    const int isize = ComponentSize(s.indices.componentType);
    if (s.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        s.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        s.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
      return Error(std::string("has sparse indices of type ") +
                   ComponentName(s.indices.componentType));
    }
    MW_ASSIGN_OR_RETURN(const ViewBytes indices, View(s.indices.bufferView));
    MW_ASSIGN_OR_RETURN(const ViewBytes values, View(s.values.bufferView));
    const size_t index_bytes = n * static_cast<size_t>(isize);  // n < 2^31
    const std::optional<size_t> value_bytes = CheckedMul(n, element);
    if (s.indices.byteOffset < 0 ||
        static_cast<size_t>(s.indices.byteOffset) > indices.size ||
        index_bytes >
            indices.size - static_cast<size_t>(s.indices.byteOffset)) {
      return Error("has sparse indices past the end of their bufferView");
    }
    if (s.values.byteOffset < 0 || !value_bytes ||
        static_cast<size_t>(s.values.byteOffset) > values.size ||
        *value_bytes > values.size - static_cast<size_t>(s.values.byteOffset)) {
      return Error("has sparse values past the end of their bufferView");
    }
    const unsigned char* ip = indices.data + s.indices.byteOffset;
    const unsigned char* vp = values.data + s.values.byteOffset;
    for (size_t k = 0; k < n; ++k) {
      const double target =
          LoadComponent(ip + k * isize, s.indices.componentType, false);
      if (target >= static_cast<double>(a.count)) {
        return Error("has sparse index " +
                     std::to_string(static_cast<uint64_t>(target)) +
                     " out of range (" + std::to_string(a.count) +
                     " elements)");
      }
      const size_t t = static_cast<size_t>(target);
      for (int c = 0; c < components; ++c) {
        out.values[t * components + c] = LoadComponent(
            vp + k * element + c * csize, a.componentType, a.normalized);
      }
    }
    return Status::Ok();
  }

  const tinygltf::Model& model_;
  const std::string& context_;
  const AccessorSpec& spec_;
  int index_;
};

}  // namespace

Result<AccessorValues> ReadAccessor(const tinygltf::Model& model, int index,
                                    const AccessorSpec& spec,
                                    const std::string& context) {
  return AccessorReader(model, context, spec, index).Read();
}

}  // namespace meshwave
