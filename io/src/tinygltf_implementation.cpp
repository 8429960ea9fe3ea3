// tinygltf's implementation (the header tiny_gltf.h of Debian's libtinygltf-dev), compiled once for read_gltf.cpp,
// without image decoding (TINYGLTF_NO_STB_IMAGE, set by io/CMakeLists.txt with the other options) and without the
// project's warnings: third-party code, kept as Debian ships it.
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
