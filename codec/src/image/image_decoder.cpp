#include "image/image_decoder.h"

#include <cstdio>

namespace meshwave {

ImageFormat SniffImageFormat(std::string_view bytes) {
  if (bytes.starts_with("\x89PNG\r\n\x1a\n")) return ImageFormat::kPng;
  if (bytes.starts_with("\xff\xd8\xff")) return ImageFormat::kJpeg;
  if (bytes.size() >= 12 && bytes.starts_with("RIFF") &&
      bytes.substr(8, 4) == "WEBP") {
    return ImageFormat::kWebp;
  }
  return ImageFormat::kUnknown;
}

const char* ImageMimeType(ImageFormat format) {
  switch (format) {
    case ImageFormat::kPng:
      return "image/png";
    case ImageFormat::kJpeg:
      return "image/jpeg";
    case ImageFormat::kWebp:
      return "image/webp";
    case ImageFormat::kUnknown:
      break;
  }
  return "";
}

std::string DescribeImageBytes(std::string_view bytes) {
  if (bytes.empty()) return "empty";
  if (bytes.starts_with("GIF8")) return "GIF";
  if (bytes.starts_with("BM")) return "BMP";
  if (bytes.starts_with("\xabKTX 20\xbb")) return "KTX2";
  if (bytes.starts_with("\xabKTX 11\xbb")) return "KTX";
  if (bytes.starts_with("DDS ")) return "DDS";
  if (bytes.size() >= 12 && bytes.substr(4, 4) == "ftyp") return "AVIF/HEIF";
  std::string out = "unknown (starts";
  for (size_t i = 0; i < bytes.size() && i < 4; ++i) {
    char hex[4];
    std::snprintf(hex, sizeof hex, " %02x",
                  static_cast<unsigned>(static_cast<unsigned char>(bytes[i])));
    out += hex;
  }
  return out + ")";
}

Status CheckImageSize(uint64_t width, uint64_t height,
                      const ImageLimits& limits, std::string_view name,
                      const char* format) {
  if (width == 0 || height == 0) {
    return ParseError(std::string(name) + ": " + format +
                      " declares an empty " + std::to_string(width) + "x" +
                      std::to_string(height) + " image");
  }
  // Both are below 2^32, so the product fits in 64 bits.
  const uint64_t pixels = width * height;
  if (pixels > limits.max_pixels) {
    return Status(StatusCode::kUnsupported,
                  std::string(name) + ": " + format + " declares " +
                      std::to_string(width) + "x" + std::to_string(height) +
                      " = " + std::to_string(pixels) +
                      " pixels, more than the " +
                      std::to_string(limits.max_pixels) +
                      "-pixel limit per image (a decompression bomb, or a "
                      "texture to downscale)");
  }
  if (pixels * 4 > limits.max_bytes) {
    return Status(StatusCode::kUnsupported,
                  std::string(name) + ": " + format + " declares " +
                      std::to_string(width) + "x" + std::to_string(height) +
                      " pixels, which would take the decoded images of this "
                      "mesh past their byte limit (" +
                      std::to_string(limits.max_bytes) + " bytes were left)");
  }
  return Status::Ok();
}

Result<DecodedImage> DecodeImage(std::string_view bytes,
                                 const ImageLimits& limits,
                                 std::string_view name) {
  switch (SniffImageFormat(bytes)) {
    case ImageFormat::kPng:
      return DecodePng(bytes, limits, name);
    case ImageFormat::kJpeg:
      return DecodeJpeg(bytes, limits, name);
    case ImageFormat::kWebp:
      return DecodeWebp(bytes, limits, name);
    case ImageFormat::kUnknown:
      break;
  }
  return Status(StatusCode::kUnsupported,
                std::string(name) + ": image format " +
                    DescribeImageBytes(bytes) +
                    " is not supported (use PNG, JPEG or WebP)");
}

}  // namespace meshwave
