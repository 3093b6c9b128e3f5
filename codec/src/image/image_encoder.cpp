// The image encoders. libpng reports errors by longjmp to the last setjmp:
// every libpng call that may fail runs inside one small function whose
// frame holds only trivially destructible locals, so a longjmp never skips
// a C++ destructor (as in png_decoder.cpp). TurboJPEG keeps libjpeg's
// longjmp inside the library and returns -1.
#include "image/image_encoder.h"

#include <png.h>
#include <turbojpeg.h>
#include <webp/encode.h>

#include <csetjmp>
#include <cstdio>
#include <string>
#include <vector>

namespace meshwave {
namespace {

Status CheckView(const ImageView& image, const char* format) {
  if (image.pixels == nullptr || image.width == 0 || image.height == 0) {
    return InvalidArgument(std::string(format) + " encoder: an empty image");
  }
  if (image.channels != 3 && image.channels != 4) {
    return InvalidArgument(std::string(format) + " encoder: " + std::to_string(image.channels) +
                           " channels (3 or 4)");
  }
  // Both formats store sides in 16 (JPEG) or 31 bits; the atlas stays far
  // below JPEG's 65,535.
  if (image.width > 65535 || image.height > 65535) {
    return InvalidArgument(std::string(format) + " encoder: " + std::to_string(image.width) +
                           " x " + std::to_string(image.height) + " exceeds 65,535 a side");
  }
  return Status::Ok();
}

class TurboJpegCompressor {
 public:
  TurboJpegCompressor() : handle_(tjInitCompress()) {}
  TurboJpegCompressor(const TurboJpegCompressor&) = delete;
  TurboJpegCompressor& operator=(const TurboJpegCompressor&) = delete;
  ~TurboJpegCompressor() {
    if (handle_ != nullptr) tjDestroy(handle_);
  }
  tjhandle get() const { return handle_; }

 private:
  tjhandle handle_;
};

struct PngOutput {
  std::string* bytes;
  char message[200];  // the last error libpng reported
};

void OnPngWriteError(png_structp png, png_const_charp message) {
  auto* output = static_cast<PngOutput*>(png_get_error_ptr(png));
  std::snprintf(output->message, sizeof output->message, "%s", message);
  png_longjmp(png, 1);
}

void OnPngWriteWarning(png_structp, png_const_charp) {}

void WritePngBytes(png_structp png, png_bytep data, size_t length) {
  auto* output = static_cast<PngOutput*>(png_get_io_ptr(png));
  output->bytes->append(reinterpret_cast<const char*>(data), length);
}

void FlushPng(png_structp) {}

// Writes the whole image; false after an error.
bool WritePng(png_structp png, png_infop info, const ImageView* image, png_bytepp rows,
              int compression) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_compression_level(png, compression);
  png_set_IHDR(png, info, image->width, image->height, 8,
               image->channels == 4 ? PNG_COLOR_TYPE_RGB_ALPHA : PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  return true;
}

class PngWriteGuard {
 public:
  PngWriteGuard(png_structp png, png_infop info) : png_(png), info_(info) {}
  PngWriteGuard(const PngWriteGuard&) = delete;
  PngWriteGuard& operator=(const PngWriteGuard&) = delete;
  ~PngWriteGuard() { png_destroy_write_struct(&png_, &info_); }

 private:
  png_structp png_;
  png_infop info_;
};

}  // namespace

Result<std::string> EncodeJpeg(const ImageView& image, const JpegEncodeOptions& options) {
  MW_RETURN_IF_ERROR(CheckView(image, "JPEG"));
  if (options.quality < 1 || options.quality > 100) {
    return InvalidArgument("JPEG encoder: quality " + std::to_string(options.quality) +
                           " (1..100)");
  }
  TurboJpegCompressor compressor;
  if (compressor.get() == nullptr) {
    return Status(StatusCode::kInternal, "libjpeg-turbo: cannot create an encoder");
  }
  unsigned char* out = nullptr;
  unsigned long size = 0;
  const int pitch = static_cast<int>(image.width) * image.channels;
  const int result = tjCompress2(
      compressor.get(), image.pixels, static_cast<int>(image.width), pitch,
      static_cast<int>(image.height), image.channels == 4 ? TJPF_RGBA : TJPF_RGB, &out, &size,
      options.subsample_chroma ? TJSAMP_420 : TJSAMP_444, options.quality, TJFLAG_ACCURATEDCT);
  if (result != 0) {
    if (out != nullptr) tjFree(out);
    return Status(StatusCode::kInternal,
                  std::string("JPEG encoder: ") + tjGetErrorStr2(compressor.get()));
  }
  std::string bytes(reinterpret_cast<const char*>(out), size);
  tjFree(out);
  return bytes;
}

Result<std::string> EncodeWebp(const ImageView& image, int quality) {
  MW_RETURN_IF_ERROR(CheckView(image, "WebP"));
  if (quality < 0 || quality > 100) {
    return InvalidArgument("WebP encoder: quality " + std::to_string(quality) + " (0..100)");
  }
  if (image.width > WEBP_MAX_DIMENSION || image.height > WEBP_MAX_DIMENSION) {
    return InvalidArgument("WebP encoder: " + std::to_string(image.width) + " x " +
                           std::to_string(image.height) + " pixels (at most " +
                           std::to_string(WEBP_MAX_DIMENSION) + " a side)");
  }
  WebPConfig config;
  WebPPicture picture;
  if (!WebPConfigPreset(&config, WEBP_PRESET_DEFAULT, static_cast<float>(quality)) ||
      !WebPPictureInit(&picture)) {
    return Status(StatusCode::kInternal, "libwebp: version mismatch");
  }
  config.thread_level = 0;  // the same bytes on every machine
  picture.use_argb = 0;
  picture.width = static_cast<int>(image.width);
  picture.height = static_cast<int>(image.height);
  WebPMemoryWriter writer;
  WebPMemoryWriterInit(&writer);
  picture.writer = WebPMemoryWrite;
  picture.custom_ptr = &writer;
  const int stride = static_cast<int>(image.width) * image.channels;
  const bool imported = image.channels == 4
                            ? WebPPictureImportRGBA(&picture, image.pixels, stride)
                            : WebPPictureImportRGB(&picture, image.pixels, stride);
  const bool encoded = imported && WebPEncode(&config, &picture);
  const WebPEncodingError error = picture.error_code;
  WebPPictureFree(&picture);
  std::string bytes(reinterpret_cast<const char*>(writer.mem), writer.size);
  WebPMemoryWriterClear(&writer);
  if (!encoded) {
    return Status(StatusCode::kInternal,
                  "WebP encoder: libwebp error " + std::to_string(static_cast<int>(error)));
  }
  return bytes;
}

Result<std::string> EncodePng(const ImageView& image, int compression) {
  MW_RETURN_IF_ERROR(CheckView(image, "PNG"));
  if (compression < 0 || compression > 9) {
    return InvalidArgument("PNG encoder: compression level " + std::to_string(compression) +
                           " (0..9)");
  }
  std::string bytes;
  PngOutput output{&bytes, {}};
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, &output, OnPngWriteError, OnPngWriteWarning);
  if (png == nullptr) return Status(StatusCode::kInternal, "libpng: cannot create a writer");
  png_infop info = png_create_info_struct(png);
  PngWriteGuard guard(png, info);
  if (info == nullptr) return Status(StatusCode::kInternal, "libpng: cannot create a writer");
  png_set_write_fn(png, &output, WritePngBytes, FlushPng);
  const size_t row_bytes = size_t{image.width} * static_cast<size_t>(image.channels);
  std::vector<png_bytep> rows(image.height);
  for (uint32_t y = 0; y < image.height; ++y) {
    // libpng's row pointers are not const; it only reads them when writing.
    rows[y] = const_cast<png_bytep>(image.pixels + y * row_bytes);
  }
  if (!WritePng(png, info, &image, rows.data(), compression)) {
    return Status(StatusCode::kInternal, std::string("PNG encoder: ") + output.message);
  }
  return bytes;
}

}  // namespace meshwave
