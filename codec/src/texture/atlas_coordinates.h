// Texture coordinates of a semi-regular mesh's faces from the atlas alone
// (docs/FORMAT.md 2.4): the one computation the decoder, the glTF writer
// and the WebAssembly bindings share. A face of level j descends from base
// face F >> 2j; its corners' barycentric coordinates in that base face
// follow the child pattern of meshwave/semiregular.h (each child's corners
// are its parent's corners and edge midpoints), and the atlas maps
// barycentric coordinates affinely, so a child's texel corners are its
// parent's texel corners and their midpoints.
#ifndef MESHWAVE_TEXTURE_ATLAS_COORDINATES_H_
#define MESHWAVE_TEXTURE_ATLAS_COORDINATES_H_

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "texture/atlas_layout.h"

namespace meshwave {

// The atlas corners of base face f of the stream: its triangle in the atlas
// (face_triangles[f] = 3 t + r: triangle t, the face's corner i on the
// triangle's corner (i + r) mod 3; empty face_triangles: t = f, r = 0).
// Inputs validated (ValidateTexture): f < atlas.base_faces().
std::array<AtlasPoint, 3> BaseFaceCorners(const AtlasLayout& atlas,
                                          std::span<const uint32_t> face_triangles, uint32_t f);

// Per face of level `level` (4^level faces per base face, in the canonical
// order), per corner, its UV = (x / width, y / height): 6 floats a face,
// u0 v0 u1 v1 u2 v2.
std::vector<float> AtlasCoordinates(const AtlasLayout& atlas,
                                    std::span<const uint32_t> face_triangles, int level);

}  // namespace meshwave

#endif  // MESHWAVE_TEXTURE_ATLAS_COORDINATES_H_
