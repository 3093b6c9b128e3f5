// How many texels an asset's textures spend on its surface: what the atlas
// of a bake should hold to keep their detail.
#ifndef MESHWAVE_TEXTURE_TEXTURE_DENSITY_H_
#define MESHWAVE_TEXTURE_TEXTURE_DENSITY_H_

#include "meshwave/mesh_asset.h"

namespace meshwave {

// The sum over faces of the face's UV area (after its slot's transform)
// times its image's texels: the base-colour image, else the first other
// map its material has (emissive, metallic-roughness, normal, occlusion).
// Tiled textures count once per repeat. 0 without UVs or images.
double TexelsOfOriginal(const MeshAsset& asset);

}  // namespace meshwave

#endif  // MESHWAVE_TEXTURE_TEXTURE_DENSITY_H_
