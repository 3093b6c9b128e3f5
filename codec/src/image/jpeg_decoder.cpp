// JPEG through libjpeg-turbo's TurboJPEG API, which keeps libjpeg's longjmp
// error handling inside the library and returns -1 with a message.
#include <turbojpeg.h>

#include <string>

#include "image/image_decoder.h"

namespace meshwave {
namespace {

class TurboJpegHandle {
 public:
  TurboJpegHandle() : handle_(tjInitDecompress()) {}
  TurboJpegHandle(const TurboJpegHandle&) = delete;
  TurboJpegHandle& operator=(const TurboJpegHandle&) = delete;
  ~TurboJpegHandle() {
    if (handle_ != nullptr) tjDestroy(handle_);
  }
  tjhandle get() const { return handle_; }

 private:
  tjhandle handle_;
};

}  // namespace

Result<DecodedImage> DecodeJpeg(std::string_view bytes,
                                const ImageLimits& limits,
                                std::string_view name) {
  TurboJpegHandle handle;
  if (handle.get() == nullptr) {
    return Status(StatusCode::kInternal,
                  "libjpeg-turbo: cannot create a decoder");
  }
  auto failed = [&](const char* stage) {
    return ParseError(std::string(name) + ": JPEG " + stage + ": " +
                      tjGetErrorStr2(handle.get()));
  };
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  // TurboJPEG takes the size as an unsigned long; on LP64 that is size_t.
  const unsigned long size = bytes.size();
  int width = 0;
  int height = 0;
  int subsampling = 0;
  int colorspace = 0;
  if (tjDecompressHeader3(handle.get(), data, size, &width, &height,
                          &subsampling, &colorspace) != 0) {
    return failed("header");
  }
  if (width <= 0 || height <= 0) {
    return ParseError(std::string(name) + ": JPEG declares an empty image");
  }
  MW_RETURN_IF_ERROR(CheckImageSize(static_cast<uint64_t>(width),
                                    static_cast<uint64_t>(height), limits, name,
                                    "JPEG"));
  if (colorspace == TJCS_CMYK || colorspace == TJCS_YCCK) {
    return Status(StatusCode::kUnsupported,
                  std::string(name) +
                      ": CMYK JPEG is not supported (a print colour space; "
                      "save the texture as RGB)");
  }
  DecodedImage image;
  image.width = static_cast<uint32_t>(width);
  image.height = static_cast<uint32_t>(height);
  image.rgba.resize(size_t{image.width} * image.height * 4);
  // A warning (a truncated or corrupt scan, which libjpeg would fill with
  // grey) stops the decoder; so does a progressive file of more than 500
  // scans, which otherwise costs unbounded time.
  const int flags = TJFLAG_STOPONWARNING | TJFLAG_LIMITSCANS;
  if (tjDecompress2(handle.get(), data, size, image.rgba.data(), width,
                    width * 4, height, TJPF_RGBA, flags) != 0) {
    return failed("image data");
  }
  return image;
}

}  // namespace meshwave
