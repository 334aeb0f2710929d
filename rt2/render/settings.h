// rt2/render/settings.h — how a frame is rendered (RenderSettings) and from where (View):
// chosen per frame, validated before use. Of the settings, only the image's size, the samples
// and their pattern, the depth, the minimum weight, the triangle test and shadows change an
// image's bits.
#pragma once

#include "rt2/render/supersampling.h"
#include "rt2/scene/camera.h"

namespace rt2 {

// Which lights a shading point considers (light_bvh.h). Every mode gives the same image:
// the lights a mode skips are those out of range, whose contribution is exactly 0.
enum class LightCulling {
  none,       // every light, tested one by one (brute force)
  tiled,      // primary hits: the lists of their block (a 2-D tile of the image)
  clustered,  // primary hits: the lists of their block's depth slice (a 3-D cluster)
  bvh,        // every hit: a walk of the light tree from its point
};
// How tiled and clustered culling fill a tile's or cluster's list.
enum class LightLists {
  brute_force,  // every light's sphere against the cluster's box (the papers' classic)
  bvh,          // a walk of the light tree with the cluster's box (the accelerated one)
};

struct RenderSettings {
  int width = 512;
  int height = 512;
  int subpixels = 1;              // samples per pixel, >= 1
  Pattern pattern = Pattern::grid;
  int depth = 1;                  // recursion depth: 0 = no reflection/refraction rays
  float min_weight = 0.01f;       // a secondary ray whose weight is <= this is not traced
  bool watertight = false;        // triangles: the watertight test instead of the fast one
  int passes = 1;                 // the samples of each pixel are rendered in this many
                                  // passes over the image, 1 ... subpixels
  // A tile is traced in square blocks of at most block x block pixels: a block's samples
  // are one batch of rays at each stage (primary, shadow, secondary), small enough to stay
  // in the caches. 1 ... 256; the image does not depend on it.
  int block = 16;
  // Primary rays are traced in packets of 4 x 4 pixels of one sample, shadow rays in
  // packets of 16 rays to one light, secondary rays 16 at a time, each packet walking the
  // BVH together where its rays allow (rt2/kernel/packet_traverse.h); false: every ray alone.
  // The image does not depend on it.
  bool packets = true;
  // Phong and physically based hits without texture or transparency are shaded
  // kWidestLanes at a time in one SIMD pass (rt2/kernel/hit_lanes.h) when every hit
  // considers every light (no light lists) and there are at most kMaxLaneLights (8) lights;
  // a point with 4 or more lights to consider evaluates them kWidestLanes at a time
  // (rt2/kernel/light_terms.h); a pass's misses read the sky in lanes. false: one hit, one
  // light, one miss at a time. The image does not depend on it.
  bool shading_lanes = true;
  // Lights: which ones each shading point considers (tiled and clustered culling use the
  // lists for primary hits and the light tree for the others), how the lists are filled,
  // and how many depth slices (1 ... 256) a block has for clustered culling: exponentially
  // spaced between its nearest and farthest primary hit, as clustered shading slices the
  // view frustum. None changes the image; scripts/sweep-many-lights compares them.
  LightCulling light_culling = LightCulling::clustered;
  LightLists light_lists = LightLists::bvh;
  int light_slices = 16;
  // false: no shadow rays; every light reaches every point that faces it (for measuring
  // what shadows cost).
  bool shadows = true;
  // Time each stage of the kernel into RayCounts::stages (a clock read per stage and batch,
  // so off unless asked for).
  bool stage_times = false;

  // Throws rt2::Error for width/height < 1 or > 65535, subpixels < 1 or > 65536,
  // depth < 0 or > 1'000'000, min_weight NaN or outside [0, 1], passes < 1 or >
  // subpixels, block or light_slices < 1 or > 256.
  void validate() const;
};

// What a frame renders: where from, and how.
struct View {
  Camera camera;
  RenderSettings settings;
};

}  // namespace rt2
