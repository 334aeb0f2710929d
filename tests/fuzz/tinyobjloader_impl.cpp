// tests/fuzz/tinyobjloader_impl.cpp — tinyobjloader's implementation, compiled from its
// header into the fuzz targets so that it is instrumented (coverage, ASan, UBSan) like rt2's
// own code; the prebuilt -ltinyobjloader is not linked. Built by scripts/fuzz.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
