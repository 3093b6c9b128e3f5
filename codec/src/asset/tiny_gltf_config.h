// tinygltf (Debian's libtinygltf-dev: the header, with nlohmann-json) as
// meshwave builds it: compiled into our library (tiny_gltf_impl.cpp) rather
// than linked from Debian's libtinygltf.so, so that these switches hold and
// the sanitizer and fuzzing builds instrument it:
//   TINYGLTF_NO_FS: no default file access at all (our FsCallbacks read a
//     FileSet only; the default ExpandFilePath once ran wordexp);
//   TINYGLTF_NO_STB_IMAGE, TINYGLTF_NO_STB_IMAGE_WRITE: no stb_image (our
//     loader keeps the encoded bytes; image/ decodes them with libpng,
//     libjpeg-turbo and libwebp, with limits);
//   TINYGLTF_NO_EXTERNAL_IMAGE: image files are read by us, so that a
//     missing one is an error (tinygltf makes it a warning).
// Include this header, never <tiny_gltf.h> directly.
#ifndef MESHWAVE_ASSET_TINY_GLTF_CONFIG_H_
#define MESHWAVE_ASSET_TINY_GLTF_CONFIG_H_

#define TINYGLTF_NO_FS
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#endif  // MESHWAVE_ASSET_TINY_GLTF_CONFIG_H_
