// The one translation unit that compiles tinygltf's implementation, with
// the switches of tiny_gltf_config.h.
// tinygltf 2.7's writer uses std::ofstream even with TINYGLTF_NO_FS, which
// leaves out the include.
#include <fstream>

#define TINYGLTF_IMPLEMENTATION
#include "asset/tiny_gltf_config.h"
