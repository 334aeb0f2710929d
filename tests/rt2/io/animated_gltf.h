// tests/rt2/io/animated_gltf.h — a small animated glTF for the tests: a unit cube (node 1)
// under a parent (node 0) that turns and steps, the cube's own scale a cubic spline, a
// point light (node 2) and the camera (node 3) carried by animated nodes; animation 0
// ("spin", 2 s) and animation 1 ("hop", 1 s: only node 0's translation). Its keys, for
// oracles, are the constants below.
#pragma once

#include <string>
#include <vector>

#include "tests/rt2/io/gltf_file.h"

namespace rt2::test {

// "spin": node 0 rotation LINEAR (about y: 0, 90, 180 degrees at 0, 1, 2 s),
// node 0 translation STEP (x = 0, 1, 2 at 0, 1, 2 s); node 1 scale CUBICSPLINE of
// s(t) = 1 + t^2 / 4 on every axis (keys and tangents at 0 and 2 s); node 3 (the camera)
// translation LINEAR from (0, 1, 6) to (0, 2, 8) over 0 ... 2 s.
inline const std::vector<float> kSpinTimes = {0.0f, 1.0f, 2.0f};
inline const std::vector<float> kSpinRotations = {0, 0, 0, 1, 0, 0.70710677f, 0, 0.70710677f,
                                                  0, 1, 0, 0};
inline const std::vector<float> kSpinSteps = {0, 0, 0, 1, 0, 0, 2, 0, 0};
inline const std::vector<float> kScaleTimes = {0.0f, 2.0f};
// in-tangent, value, out-tangent per key: s(0) = 1, s'(0) = 0; s(2) = 2, s'(2) = 1
inline const std::vector<float> kScaleKeys = {0, 0, 0, 1, 1, 1, 0, 0, 0,
                                              1, 1, 1, 2, 2, 2, 1, 1, 1};
inline const std::vector<float> kCameraKeys = {0, 1, 6, 0, 2, 8};
// "hop": node 0 translation LINEAR from y = 0 to y = 3 over 0 ... 1 s.
inline const std::vector<float> kHopTimes = {0.0f, 1.0f};
inline const std::vector<float> kHopKeys = {0, 0, 0, 0, 3, 0};

// The cube's corners, as the file holds them (node 1's local space).
inline std::vector<float> cube_corners() {
  std::vector<float> p;
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) p.push_back((i >> k) & 1 ? 0.5f : -0.5f);
  return p;
}

// The file as JSON text with `extra_animations` (each a JSON object, after "spin" and "hop").
inline std::string animated_gltf(const std::vector<std::string>& extra_animations = {}) {
  GltfFile f;
  f.floats(cube_corners(), "VEC3", 3);  // 0
  const std::vector<unsigned> faces = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                                       2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
  f.accessor(faces, 5125, "SCALAR", faces.size());  // 1
  f.floats(kSpinTimes, "SCALAR", 1);                 // 2
  f.floats(kSpinRotations, "VEC4", 4);               // 3
  f.floats(kSpinSteps, "VEC3", 3);                   // 4
  f.floats(kScaleTimes, "SCALAR", 1);                // 5
  f.floats(kScaleKeys, "VEC3", 3);                   // 6
  f.floats(kCameraKeys, "VEC3", 3);                  // 7
  f.floats(kHopTimes, "SCALAR", 1);                  // 8
  f.floats(kHopKeys, "VEC3", 3);                     // 9
  std::string animations =
      R"([{"name":"spin","channels":[)"
      R"({"sampler":0,"target":{"node":0,"path":"rotation"}},)"
      R"({"sampler":1,"target":{"node":0,"path":"translation"}},)"
      R"({"sampler":2,"target":{"node":1,"path":"scale"}},)"
      R"({"sampler":3,"target":{"node":3,"path":"translation"}}],"samplers":[)"
      R"({"input":2,"output":3},{"input":2,"output":4,"interpolation":"STEP"},)"
      R"({"input":5,"output":6,"interpolation":"CUBICSPLINE"},{"input":5,"output":7}]},)"
      R"({"name":"hop","channels":[{"sampler":0,"target":{"node":0,"path":"translation"}}],)"
      R"("samplers":[{"input":8,"output":9}]})";
  for (const std::string& a : extra_animations) animations += "," + a;
  animations += "]";
  return f.json(
      R"(,"extensionsUsed":["KHR_lights_punctual"],)"
      R"("extensions":{"KHR_lights_punctual":{"lights":[{"type":"point","intensity":10}]}},)"
      R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
      R"("cameras":[{"type":"perspective","perspective":{"yfov":0.8,"znear":0.1}}],)"
      R"("nodes":[{"children":[1,2]},{"mesh":0,"translation":[0,0.5,0]},)"
      R"({"translation":[0,3,0],"extensions":{"KHR_lights_punctual":{"light":0}}},)"
      R"({"camera":0,"translation":[0,1,6]}],"scenes":[{"nodes":[0,3]}],"animations":)" +
      animations);
}

}  // namespace rt2::test
