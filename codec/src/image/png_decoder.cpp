// PNG through libpng's full API. libpng reports errors by longjmp to the
// last setjmp: every call that may fail runs inside one of the small
// functions below, whose frames hold only trivially destructible locals, so
// a longjmp never skips a C++ destructor. The buffers they fill belong to
// the caller.
#include <png.h>

#include <algorithm>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "image/image_decoder.h"

namespace meshwave {
namespace {

// Cap on the memory one ancillary chunk may take once decompressed (iCCP,
// zTXt, iTXt): libpng's own default, made explicit.
constexpr png_alloc_size_t kMaxChunkBytes = 8'000'000;

// Headroom over the largest row libpng may hold (16-bit RGBA of the widest
// image the pixel limit allows) for its chunk and zlib buffers.
constexpr size_t kAllocationSlack = 16u << 20;

struct PngInput {
  const unsigned char* data;
  size_t size;
  size_t offset;
  size_t max_allocation;  // the largest block libpng may ask for
  char message[200];      // the last error libpng reported
};

// libpng's allocations go through here so that no length read from the file
// (a chunk's, an embedded profile's) makes it take more than the image could
// need: a refused block is an error libpng reports, not an out-of-memory.
png_voidp AllocateForPng(png_structp png, png_alloc_size_t size) {
  auto* input = static_cast<PngInput*>(png_get_mem_ptr(png));
  if (size > input->max_allocation) return nullptr;
  return std::malloc(size);
}

void FreeForPng(png_structp, png_voidp block) { std::free(block); }

void OnPngError(png_structp png, png_const_charp message) {
  auto* input = static_cast<PngInput*>(png_get_error_ptr(png));
  std::snprintf(input->message, sizeof input->message, "%s", message);
  png_longjmp(png, 1);
}

void OnPngWarning(png_structp, png_const_charp) {}

void ReadPngBytes(png_structp png, png_bytep out, size_t length) {
  auto* input = static_cast<PngInput*>(png_get_io_ptr(png));
  if (length > input->size - input->offset) {
    png_error(png, "the file ends early (truncated)");
  }
  std::memcpy(out, input->data + input->offset, length);
  input->offset += length;
}

// Reads the chunks up to the image data; false after an error.
bool ReadHeader(png_structp png, png_infop info, png_uint_32* width,
                png_uint_32* height) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_info(png, info);
  *width = png_get_image_width(png, info);
  *height = png_get_image_height(png, info);
  return true;
}

// Asks for 8-bit RGBA whatever the stored layout; returns the row size
// libpng will produce, 0 after an error.
size_t RequestRgba8(png_structp png, png_infop info) {
  if (setjmp(png_jmpbuf(png))) return 0;
  const png_byte color = png_get_color_type(png, info);
  const png_byte depth = png_get_bit_depth(png, info);
  const bool has_trns = png_get_valid(png, info, PNG_INFO_tRNS) != 0;
  if (depth == 16) png_set_scale_16(png);
  if (color == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (color == PNG_COLOR_TYPE_GRAY && depth < 8) {
    png_set_expand_gray_1_2_4_to_8(png);
  }
  if (has_trns) png_set_tRNS_to_alpha(png);
  if (color == PNG_COLOR_TYPE_GRAY || color == PNG_COLOR_TYPE_GRAY_ALPHA) {
    png_set_gray_to_rgb(png);
  }
  if ((color & PNG_COLOR_MASK_ALPHA) == 0 && !has_trns) {
    png_set_filler(png, 0xff, PNG_FILLER_AFTER);
  }
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  return png_get_rowbytes(png, info);
}

bool ReadRows(png_structp png, png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_image(png, rows);
  png_read_end(png, nullptr);
  return true;
}

// Frees libpng's structures on every way out.
class PngReadGuard {
 public:
  PngReadGuard(png_structp png, png_infop info) : png_(png), info_(info) {}
  PngReadGuard(const PngReadGuard&) = delete;
  PngReadGuard& operator=(const PngReadGuard&) = delete;
  ~PngReadGuard() { png_destroy_read_struct(&png_, &info_, nullptr); }

 private:
  png_structp png_;
  png_infop info_;
};

}  // namespace

Result<DecodedImage> DecodePng(std::string_view bytes,
                               const ImageLimits& limits,
                               std::string_view name) {
  // The pixel limit bounds the widest row: one row of max_pixels pixels.
  const uint64_t widest_row = std::min<uint64_t>(limits.max_pixels, 0x7fffffff);
  PngInput input{reinterpret_cast<const unsigned char*>(bytes.data()),
                 bytes.size(),
                 0,
                 static_cast<size_t>(widest_row * 8 + kAllocationSlack),
                 {}};
  auto failed = [&](const char* stage) {
    return ParseError(
        std::string(name) + ": PNG " + stage + ": " +
        (input.message[0] != '\0' ? input.message : "corrupt data"));
  };
  png_structp png = png_create_read_struct_2(PNG_LIBPNG_VER_STRING, &input,
                                             OnPngError, OnPngWarning, &input,
                                             AllocateForPng, FreeForPng);
  if (png == nullptr) {
    return Status(StatusCode::kInternal, "libpng: cannot create a reader");
  }
  png_infop info = png_create_info_struct(png);
  PngReadGuard guard(png, info);
  if (info == nullptr) {
    return Status(StatusCode::kInternal, "libpng: cannot create a reader");
  }
  png_set_read_fn(png, &input, ReadPngBytes);
  png_set_chunk_malloc_max(png, kMaxChunkBytes);
  // Only IHDR, PLTE, tRNS, IDAT and IEND shape the pixels we keep (no gamma
  // or colour management): every other chunk is skipped unread.
  png_set_keep_unknown_chunks(png, PNG_HANDLE_CHUNK_NEVER, nullptr, -1);
  // libpng's own per-side limit is 1,000,000; the pixel count is ours.
  png_set_user_limits(png, 0x7fffffff, 0x7fffffff);

  png_uint_32 width = 0;
  png_uint_32 height = 0;
  if (!ReadHeader(png, info, &width, &height)) return failed("header");
  MW_RETURN_IF_ERROR(CheckImageSize(width, height, limits, name, "PNG"));
  const size_t row_bytes = RequestRgba8(png, info);
  if (row_bytes == 0) return failed("header");
  if (row_bytes != size_t{width} * 4) {
    return Status(StatusCode::kInternal,
                  std::string(name) + ": libpng gives rows of " +
                      std::to_string(row_bytes) + " bytes for RGBA width " +
                      std::to_string(width));
  }
  DecodedImage image;
  image.width = width;
  image.height = height;
  image.rgba.resize(row_bytes * height);
  std::vector<png_bytep> rows(height);
  for (png_uint_32 y = 0; y < height; ++y) {
    rows[y] = image.rgba.data() + y * row_bytes;
  }
  if (!ReadRows(png, rows.data())) return failed("image data");
  return image;
}

}  // namespace meshwave
