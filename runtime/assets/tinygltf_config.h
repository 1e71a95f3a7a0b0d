#pragma once
// The one configuration of tinygltf used by every translation unit that includes it (its macros
// change declarations, so all includers must agree).
//
// Not built with TINYGLTF_ENABLE_DRACO: tinygltf 2.7's Draco path indexes bufferViews, buffers and
// accessors from the file without bounds checks, dereferences a null attribute for an unknown Draco
// id, ignores decode failures (leaving the compressed bytes in place of vertices) and overwrites the
// accessor counts it should be checked against. draco_decode.cpp decodes KHR_draco_mesh_compression
// with the same Draco library after validation instead.
// Images are decoded by image_decode.cpp (PNG and JPEG, size-checked before decoding) and external
// files are opened only through the loader's own callbacks, which keep them inside the file's folder.
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#define TINYGLTF_NO_FS
#include <tiny_gltf.h>
