// Decoding the images of an asset, shared by the glTF and OBJ readers:
// sniffs the format, decodes with the asset's limits and charges the
// decoded bytes to a budget shared by all images of the asset.
#ifndef MESHWAVE_ASSET_ASSET_IMAGE_H_
#define MESHWAVE_ASSET_ASSET_IMAGE_H_

#include <cstdint>

#include "meshwave/mesh_asset.h"
#include "meshwave/status.h"

namespace meshwave {

// Fills image.mime_type (from the bytes; "" when unknown), width, height
// and rgba from image.encoded, messages naming image.name. On success the
// decoded size is taken from *decoded_bytes_left; on failure the image is
// left undecoded.
Status DecodeAssetImage(AssetImage& image, const AssetLimits& limits,
                        uint64_t* decoded_bytes_left);

}  // namespace meshwave

#endif  // MESHWAVE_ASSET_ASSET_IMAGE_H_
