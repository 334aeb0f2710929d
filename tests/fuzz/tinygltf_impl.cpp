// tests/fuzz/tinygltf_impl.cpp — tinygltf's implementation, compiled from its header into the
// fuzz targets so that it is instrumented (coverage, ASan, UBSan) like rt2's own code; the
// prebuilt -ltinygltf is not linked. Without stb_image (scripts/fuzz defines
// TINYGLTF_NO_STB_IMAGE and TINYGLTF_NO_STB_IMAGE_WRITE for every file): rt2 installs its
// own image callback, which keeps the bytes undecoded. External images are read, as
// Debian's library reads them. Built by scripts/fuzz.
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
