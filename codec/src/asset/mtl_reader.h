// Wavefront MTL material libraries, mapped onto glTF's metallic-roughness
// Material: Kd -> base colour factor; map_Kd -> base colour texture;
// map_Bump, bump, norm -> normal texture (-bm -> normal scale; exporters
// such as Blender's write normal maps there); d, or 1 - Tr -> alpha (blend
// when below 1); Ke, map_Ke -> emissive; Pr, Pm -> roughness, metallic
// (metallic is 0 unless Pm says otherwise, as for any non-PBR MTL).
// Texture options are parsed by their arity: -o and -s (offset and scale,
// as three.js and Blender read them) become the slot's transform, -clamp on
// its wrap mode, -bm the normal scale; the others are skipped. Texture file
// names are the rest of the line after the options (they may hold spaces);
// backslashes, which Windows exporters write, are read as '/'.
#ifndef MESHWAVE_ASSET_MTL_READER_H_
#define MESHWAVE_ASSET_MTL_READER_H_

#include <string>
#include <string_view>
#include <vector>

#include "meshwave/mesh_asset.h"
#include "meshwave/status.h"

namespace meshwave {

// A material with its texture slots naming files (resolved in the file
// set, relative to the MTL file) instead of images.
struct MtlMaterial {
  Material material;  // texture slots: image -1, see the *_file names
  std::string base_color_file;
  std::string normal_file;
  std::string emissive_file;
};

// Parses one MTL file. `name` is its name in the file set (messages, and
// the folder texture names are relative to). Statements the model does not
// carry are listed in one note.
Result<std::vector<MtlMaterial>> ParseMtl(std::string_view bytes,
                                          std::string_view name,
                                          std::vector<std::string>* notes);

}  // namespace meshwave

#endif  // MESHWAVE_ASSET_MTL_READER_H_
