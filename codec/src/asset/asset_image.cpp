#include "asset/asset_image.h"

#include <utility>

#include "image/image_decoder.h"

namespace meshwave {

Status DecodeAssetImage(AssetImage& image, const AssetLimits& limits,
                        uint64_t* decoded_bytes_left) {
  image.mime_type = ImageMimeType(SniffImageFormat(image.encoded));
  ImageLimits image_limits;
  image_limits.max_pixels = limits.max_image_pixels;
  image_limits.max_bytes = *decoded_bytes_left;
  MW_ASSIGN_OR_RETURN(DecodedImage decoded,
                      DecodeImage(image.encoded, image_limits, image.name));
  *decoded_bytes_left -= decoded.rgba.size();
  image.width = decoded.width;
  image.height = decoded.height;
  image.rgba = std::move(decoded.rgba);
  return Status::Ok();
}

}  // namespace meshwave
