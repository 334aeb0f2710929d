// rt2/kernel/tracer.h — the render kernel: Whitted ray tracing with Phong shading (thesis 3.1,
// 3.2), or physically based shading for the materials that ask for it (pbr_shade.h), over
// batches of rays, as a template over the triangle test.
//
// A tile is traced in blocks of pixels (RenderSettings::block). For a block and a range of
// samples the kernel runs stages over batches, breadth first through the ray tree:
//   1. generate: one primary ray per sample of every pixel of the block, in packets of one
//      sample over 4 x 4 pixels;
//   2. intersect the batch (closest hit), packet by packet (secondary batches 16 rays at a
//      time, in batch order): rt2/kernel/query.h's packet queries, or one ray at a time when
//      RenderSettings::packets is off, with the same answers;
//   3. shade the hits (Phong hits kWidestLanes at a time where the scene allows:
//      phong_lanes.h): their surface points; the lights each point considers (all of
//      them, or a list from light culling: per block or per depth slice of a block for
//      primary hits, from a walk of the light tree for the others; RenderSettings::
//      light_culling); the ambient term goes to the sample's colour at once; for each of
//      those lights in range that the surface faces, the unshadowed Phong term goes into a
//      batch of shadow rays; reflected and refracted rays whose weight passes min_weight go
//      into the next batch;
//   4. trace the shadow batch (transmittance; in packets of 16 rays to one light, grouped by
//      a stable sort unless the batch comes grouped) and add each light's term times what
//      passed, in batch order; a ray
//      from a tile or cluster to a light it provably sees whole (cluster_visibility.h) is
//      not traced: it passes 1, as its walk would return;
//   5. repeat 2 ... 4 with the next batch until it is empty or `depth` is reached;
//   6. add each sample's colour to the film, samples in index order.
// A ray's contribution is its weight (the product of the Kr / Kt factors along its path,
// per colour channel: physically based surfaces weight by Fresnel)
// times the local colour where it lands, as before; only the order in which a sample's
// terms are summed follows the stages (so images differ from the depth-first renderer of
// rt2 0.2 by rounding, RMSE below 1e-7 on the shipped scenes). Every sample is computed on
// its own, so the batches' sizes never change a pixel.
//
// Compiled per instruction set (rt2/base/isa.h) by isa_kernels.cpp: the code lives in
// rt2::RT2_ISA. Materials decide reflection, refraction and highlights at run time (a
// kernel compiled per combination of scene features measured about 1 % faster, inside the
// noise, so it was dropped).
#pragma once

#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <numbers>
#include <vector>

#include "rt2/kernel/batches.h"
#include "rt2/geometry/offset.h"
#include "rt2/geometry/optics.h"
#include "rt2/kernel/pbr_shade.h"
#include "rt2/kernel/phong_lanes.h"
#include "rt2/kernel/query.h"
#include "rt2/render/renderer.h"

namespace rt2::RT2_ISA {
namespace detail {

// Stage 3 for one hit: I_local = Ka I_amb now, and for each light of `lights` in range
// that reaches the surface the term Kd I (L·N) + Ks I (R·V)^n (times the light's range
// window, light.h) into the shadow batch, to be scaled by what passes (thesis 3.2; SPEC
// "Shading"). `lights` holds every light in range, in scene order, whatever the culling.
MLIB_INLINE void shade(const CompiledScene& sc, const PathRay& r, const SurfacePoint& s,
                  LightList lights, float pixel_angle, Batches& b, RayCounts& counts) {
  const Material& m = sc.materials[s.material];
  const vec4 weight = r.weight();
  b.colors[r.sample] += weight * (m.ambient * sc.ambient);
  ++counts.lights.points;
  counts.lights.considered += lights.count;
  if (lights.count == 0) return;
  vec4 kd = m.diffuse_at(s.p + sc.origin);  // the checker lives in world coordinates
  if (m.base_color_texture != kNoTexture) {  // MTL's map_Kd
    const TexturePoint tp = texcoords_at(sc.accel, s, sc.origin);
    kd *= sc.textures.sample(m.base_color_texture, tp.u, tp.v,
                             s.t * pixel_angle * tp.per_world);
  }
  const vec4& origin = s.above;
  const vec4 view = -r.ray.dir;
  for (std::size_t k = 0; k < lights.count; ++k) {
    const std::uint32_t li = lights[k];
    const Light& light = sc.lights[li];
    const vec4 to = light.position - origin;
    const float dist = std::sqrt(float(dot(to, to)));
    if (!in_range(light, dist)) continue;  // contributes exactly 0
    ++counts.lights.in_range;
    const vec4 l = to / dist;
    if (!(dot(l, s.ng) > 0.0f)) continue;  // the light is behind the surface (or at p)
    const float n_dot_l = dot(s.ns, l);
    if (!(n_dot_l > 0.0f)) continue;
    const bool unoccluded = lights.sees && lights.sees[k];
    ++(unoccluded ? counts.lights.unoccluded : counts.shadow);
    vec4 term = kd * n_dot_l;
    if (m.has_specular()) {
      const float r_dot_v = dot(2.0f * n_dot_l * s.ns - l, view);  // R = reflect(-L, N)
      if (r_dot_v > 0.0f) term += m.specular * std::pow(r_dot_v, m.shininess);
    }
    push_shadow_ray(b, origin, l, dist, weight, term, light, li, r.sample, unoccluded);
  }
}

// Stage 3's secondary rays: refraction (or, on total internal reflection, its share
// reflected) and reflection, when deep and heavy enough.
inline void spawn(const CompiledScene& sc, const RenderSettings& st, int depth, const PathRay& r,
                  const SurfacePoint& s, Batches& b, RayCounts& counts) {
  if (depth >= st.depth) return;
  const Material& m = sc.materials[s.material];
  if (m.transparency > 0.0f) {
    const vec4 w = r.weight() * m.transparency;
    if (heavy_enough(w, st.min_weight)) {
      const float eta = s.entering ? 1.0f / m.ior : m.ior;
      vec4 t;
      if (refract(r.ray.dir, s.ns, eta, t))
        push_path_ray(b, offset_ray_origin(s.p, -s.ng, sc.offset_scale), t, w, r,
                      RayKind::refraction, counts);
      else  // total internal reflection: the transmitted share is reflected
        push_path_ray(b, s.above, reflect(r.ray.dir, s.ns), w, r, RayKind::reflection, counts);
    }
  }
  if (m.reflectivity > 0.0f) {
    const vec4 w = r.weight() * m.reflectivity;
    if (heavy_enough(w, st.min_weight))
      push_path_ray(b, s.above, reflect(r.ray.dir, s.ns), w, r, RayKind::reflection, counts);
  }
}

// The 16 rays of a whole 4 x 4 packet (image x per column, y per row; samples sample0 +
// row * row_step + column * column_step), appended in one SIMD pass: lane by lane what
// Camera::ray_at computes, the same bits (normalize's dot product in dpps's order, and its
// rescaling path, through ray_at itself, for the lanes that need it).
inline void push_packet(const Camera& cam, const float (&image_x)[4], const float (&image_y)[4],
                        std::uint32_t sample0, std::uint32_t row_step, std::uint32_t column_step,
                        PathRays& rays) {
  using V = mlib::vfloat<mlib::kWidestLanes>;
  constexpr int kLanes = V::size;
  auto& c = rays.columns();
  c.reserve(c.size() + 16);
  const std::size_t at = c.size();
  alignas(64) float xs[16], ys[16];
  for (int l = 0; l < 16; ++l) {
    xs[l] = image_x[l % 4];
    ys[l] = image_y[l / 4];
    c.u(PathRays::kSample)[at + std::size_t(l)] =
        sample0 + std::uint32_t(l / 4) * row_step + std::uint32_t(l % 4) * column_step;
  }
  const vec4 &forward = cam.forward(), &right = cam.right(), &up = cam.up(), &eye = cam.position();
  for (int g = 0; g < 16; g += kLanes) {
    const V x = V::load(xs + g), y = V::load(ys + g);
    V d[4];
    for (int a = 0; a < 4; ++a)
      d[a] = (V::broadcast(forward[a]) + V::broadcast(right[a]) * x) + V::broadcast(up[a]) * y;
    const V len2 = (d[0] * d[0] + d[1] * d[1]) + (d[2] * d[2] + d[3] * d[3]);
    const V len = sqrt(len2);
    for (int a = 0; a < 4; ++a) {
      (d[a] / len).storeu(c.f(PathRays::kDir + a) + at + std::size_t(g));
      V::broadcast(eye[a]).storeu(c.f(PathRays::kOrg + a) + at + std::size_t(g));
    }
    for (int k = 0; k < 3; ++k) V::broadcast(1.0f).storeu(c.f(PathRays::kWeight + k) + at + std::size_t(g));
    const unsigned normal = mlib::bits((len2 >= V::broadcast(FLT_MIN)) & (len2 <= V::broadcast(FLT_MAX)));
    for (unsigned m = ~normal & ((1u << kLanes) - 1); m; m &= m - 1) {
      const int l = g + std::countr_zero(m);
      const vec4 dir = cam.ray_at(xs[l], ys[l]).dir;
      for (int a = 0; a < 4; ++a) c.f(PathRays::kDir + a)[at + std::size_t(l)] = dir[a];
    }
  }
  c.extend(16);
}

// Stage 1: the primary rays of samples [s0, s1) of the block's pixels, packet by packet:
// 4 x 4 pixels (fewer at the block's right and bottom edges) for one sample. A sample's
// colour is b.colors[((y - y0) bw + x - x0) (s1 - s0) + k - s0] whatever the ray order.
inline void generate(const Renderer& r, const Tile& block, int s0, int s1, Batches& b) {
  const RenderSettings& st = r.settings();
  const Camera& cam = r.camera();
  const auto& offsets = r.offsets();
  const int samples = s1 - s0, bw = block.x1 - block.x0;
  b.rays.clear();
  // clear + push_back, not assign(1, 0): GCC outlines vector<uint32_t>'s fill in the AVX-512
  // unit only, a std:: function with wide instructions that isa_test rightly flags
  b.packet_begin.clear();
  b.packet_begin.push_back(0);
  for (int gy = block.y0; gy < block.y1; gy += 4)
    for (int gx = block.x0; gx < block.x1; gx += 4)
      for (int k = s0; k < s1; ++k) {
        const SubpixelOffset& o = offsets[k];
        const int nx = std::min(gx + 4, block.x1) - gx, ny = std::min(gy + 4, block.y1) - gy;
        float image_x[4], image_y[4];  // per column and row of the packet (Camera::ray)
        for (int j = 0; j < nx; ++j) image_x[j] = cam.image_x(float(gx + j) + o.x, st.width, st.height);
        for (int j = 0; j < ny; ++j) image_y[j] = cam.image_y(float(gy + j) + o.y, st.height);
        if (nx == 4 && ny == 4) {
          push_packet(cam, image_x, image_y,
                      static_cast<std::uint32_t>(((gy - block.y0) * bw + gx - block.x0) * samples + k - s0),
                      static_cast<std::uint32_t>(bw * samples), static_cast<std::uint32_t>(samples),
                      b.rays);
          b.packet_begin.push_back(static_cast<std::uint32_t>(b.rays.size()));
          continue;
        }
        for (int y = gy; y < gy + ny; ++y) {
          vec4 dir[4];
          std::uint32_t sample[4];
          for (int j = 0; j < 4; ++j) {
            const int x = gx + std::min(j, nx - 1);  // a short row repeats its last ray
            dir[j] = cam.ray_at(image_x[x - gx], image_y[y - gy]).dir;
            sample[j] = static_cast<std::uint32_t>(((y - block.y0) * bw + x - block.x0) * samples +
                                                   k - s0);
          }
          b.rays.push_row(cam.position(), dir, sample, nx);
        }
        b.packet_begin.push_back(static_cast<std::uint32_t>(b.rays.size()));
      }
}

// Stage 2 for rays [begin, end) of b.rays (at most kPacketSize): b.hits[i] = the closest
// hit of ray i, found as one packet or one ray at a time.
template <bool Watertight>
void intersect(const CompiledScene& sc, const RenderSettings& st, std::size_t begin,
               std::size_t end, Batches& b, TraversalCounts& walk) {
  alignas(64) static constexpr float kNoBound[kPacketSize] = {kInfinity, kInfinity, kInfinity, kInfinity,
                                                  kInfinity, kInfinity, kInfinity, kInfinity,
                                                  kInfinity, kInfinity, kInfinity, kInfinity,
                                                  kInfinity, kInfinity, kInfinity, kInfinity};
  Hit* hits = b.hits.data() + begin;
  const int n = static_cast<int>(end - begin);
  if (st.packets) {
    closest_hit_packet<Watertight>(sc.accel, b.rays.rays(), begin, (PacketMask(1) << n) - 1, 0.0f,
                                   kNoBound, hits, &walk);
  } else {
    for (int l = 0; l < n; ++l)
      hits[l] = closest_hit<Watertight>(sc.accel, b.rays.ray(begin + std::size_t(l)), 0.0f,
                                        kInfinity, &walk);
  }
}

// Stage 3, first step: the surface point of every hit of the batch.
inline void surface_points(const CompiledScene& sc, Batches& b) {
  const std::size_t n = b.rays.size();
  b.points.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    if (b.hits[i].found())
      b.points[i] = surface_at(sc.accel, b.rays.ray(i), b.hits[i], sc.offset_scale);
}

// The depth slice (0 ... slices - 1) of depth z in [near, far]: exponentially spaced when
// near > 0 (as clustered shading slices a frustum), evenly otherwise.
inline int depth_slice(float z, float near, float far, int slices) {
  if (!(far > near)) return 0;
  const float x = near > 0.0f ? std::log(z / near) / std::log(far / near) * float(slices)
                              : (z - near) / (far - near) * float(slices);
  return x >= float(slices - 1) ? slices - 1 : (x > 0.0f ? int(x) : 0);
}

// Whether hits get light lists: culling is on, some light has a range (without one, every
// light reaches everywhere), and at most kMaxListedUnbounded lights have none (every list
// repeats those: beyond, a list per point would cost more than testing every light).
inline constexpr std::size_t kMaxListedUnbounded = 1024;
inline bool uses_light_lists(const Renderer& r) {
  const LightBvh& lights = r.scene().light_bvh;
  return r.settings().light_culling != LightCulling::none && lights.has_bounded() &&
         lights.unbounded().size() <= kMaxListedUnbounded;
}

// Stage 3, second step: the lights each hit considers (RenderSettings::light_culling), as
// lists in b.light_items.
inline void find_lights(const Renderer& r, bool primary, Batches& b, LightCounts& counts) {
  const CompiledScene& sc = r.scene();
  const RenderSettings& st = r.settings();
  const std::size_t n = b.rays.size();
  b.light_items.clear();
  b.list_begin.clear();
  b.list_begin.push_back(0);
  b.list_of.resize(n);
  b.list_sees.clear();
  // A list for the hits inside `cluster`: its lights, and which of them every hit there
  // provably sees (when shadow rays are traced at all).
  const auto add_cluster_list = [&](const Aabb& cluster) {
    b.list_sees.resize(b.list_sees.size() + b.found.size(), 0);
    if (st.shadows) {
      Aabb reach = cluster;
      for (const std::uint32_t li : b.found)
        if (sc.lights[li].has_range()) reach.grow(sc.lights[li].position);
      b.visibility.gather(sc.accel, cluster, reach);
      std::uint8_t* sees = b.list_sees.data() + b.light_items.size();
      for (std::size_t k = 0; k < b.found.size(); ++k) {
        const Light& l = sc.lights[b.found[k]];
        sees[k] = l.has_range() && b.visibility.sees(l.position);
      }
    }
  };
  const auto add_list = [&]() {
    if (b.list_sees.size() < b.light_items.size() + b.found.size())
      b.list_sees.resize(b.light_items.size() + b.found.size(), 0);
    b.light_items.insert(b.light_items.end(), b.found.begin(), b.found.end());
    b.list_begin.push_back(static_cast<std::uint32_t>(b.light_items.size()));
    ++counts.lists;
    counts.list_entries += b.found.size();
    return static_cast<std::uint32_t>(b.list_begin.size() - 2);
  };
  const auto fill = [&](const Aabb& box) {
    if (st.light_lists == LightLists::bvh)
      sc.light_bvh.lights_near(box, b.found);
    else
      sc.light_bvh.lights_near_brute_force(box, b.found);
  };
  if (primary && st.light_culling == LightCulling::tiled) {
    // One list for the block: the lights that reach its hits' bounds.
    Aabb box;
    for (std::size_t i = 0; i < n; ++i)
      if (b.hits[i].found()) box.grow(b.points[i].above);
    if (box.is_empty()) return;
    fill(box);
    add_cluster_list(box);
    const std::uint32_t list = add_list();
    std::fill(b.list_of.begin(), b.list_of.end(), list);
  } else if (primary && st.light_culling == LightCulling::clustered) {
    // A list per depth slice of the block: the lights that reach the bounds of the slice's
    // hits (the clusters the hits occupy: empty ones get none).
    const vec4& eye = r.camera().position();
    const vec4& forward = r.camera().forward();
    b.depth.resize(n);
    float near = kInfinity, far = -kInfinity;
    for (std::size_t i = 0; i < n; ++i) {
      if (!b.hits[i].found()) continue;
      b.depth[i] = dot(b.points[i].above - eye, forward);
      near = std::min(near, b.depth[i]);
      far = std::max(far, b.depth[i]);
    }
    const int slices = st.light_slices;
    b.cluster_bounds.assign(static_cast<std::size_t>(slices), Aabb());
    for (std::size_t i = 0; i < n; ++i) {
      if (!b.hits[i].found()) continue;
      const int k = depth_slice(b.depth[i], near, far, slices);
      b.list_of[i] = static_cast<std::uint32_t>(k);
      b.cluster_bounds[static_cast<std::size_t>(k)].grow(b.points[i].above);
    }
    std::uint32_t slice_list[256];
    for (int k = 0; k < slices; ++k) {
      if (b.cluster_bounds[static_cast<std::size_t>(k)].is_empty()) continue;
      fill(b.cluster_bounds[static_cast<std::size_t>(k)]);
      add_cluster_list(b.cluster_bounds[static_cast<std::size_t>(k)]);
      slice_list[k] = add_list();
    }
    for (std::size_t i = 0; i < n; ++i)
      if (b.hits[i].found()) b.list_of[i] = slice_list[b.list_of[i]];
  } else {
    // A walk of the light tree from each hit's point.
    for (std::size_t i = 0; i < n; ++i) {
      if (!b.hits[i].found()) continue;
      sc.light_bvh.lights_near(b.points[i].above, b.found);
      b.list_of[i] = add_list();
    }
  }
}

// Stage 3 for one hit: Phong inline; the physically based step is a call of its own
// (pbr_shade.h), so that it does not weigh on the thesis's path. Forced inline at both
// call sites of shade_hits: a surface point built in one place and read through a pointer
// in another costs a store-forwarding stall per hit (the headline frame took 30 % longer).
MLIB_INLINE void shade_hit(const CompiledScene& sc, const RenderSettings& st, int depth,
                           const PathRay& pr, const SurfacePoint& s, LightList lights,
                           float pixel_angle, Batches& b, RayCounts& counts) {
  if (sc.materials[s.material].model == Shading::pbr) {
    shade_and_spawn_pbr(sc, st, depth, pr, s, lights, pixel_angle, b, counts);
  } else {
    shade(sc, pr, s, lights, pixel_angle, b, counts);
    spawn(sc, st, depth, pr, s, b, counts);
  }
}

// Stage 3, last step: each hit shaded with its lights and its secondary rays spawned; a
// miss takes the background. With lists, the surface points are b.points (the first step
// made them, the second used them); without, every hit considers every light and its
// surface point is made here (the first two steps are skipped: one pass over the hits).
// kHitLanes rays at a time: without lists and with at most kMaxLaneLights lights, the
// Phong hits among them are shaded in one SIMD pass (phong_lanes.h; RenderSettings::
// shading_lanes), the others one by one; each ray's results are then added in batch
// order, the same bits either way.
inline void shade_hits(const Renderer& r, bool lists, int depth, Batches& b, RayCounts& counts) {
  const CompiledScene& sc = r.scene();
  const RenderSettings& st = r.settings();
  // the angle a pixel spans at the image centre: a texture lookup's footprint per distance
  const float pixel_angle =
      2.0f * std::tan(r.camera().fov() * (std::numbers::pi_v<float> / 360.0f)) / float(st.height);
  const bool in_lanes = st.shading_lanes && !lists && sc.lights.size() <= kMaxLaneLights;
  PhongLanes phong;  // every lane a pass reads, gather_lanes writes
  const std::uint32_t* samples = b.rays.columns().u(PathRays::kSample);
  const std::size_t n = b.rays.size();
  for (std::size_t first = 0; first < n; first += kHitLanes) {
    const std::size_t end = std::min(first + kHitLanes, n);
    unsigned shaded = 0;  // the lanes shaded in SIMD
    if (in_lanes) {
      shaded = gather_lanes(sc, b, first, end, phong);
      if (shaded) {
        shade_lanes(sc, st, depth, shaded, b.rays, first, phong);
        count_lanes(sc, phong, shaded, counts);
      }
    }
    // When no other ray of the pass appends rays (they all missed), the lanes' rays are
    // appended a vector at a time (emit_lanes), with several lights only where no two rays
    // share a sample (primary rays; a scene whose hits never fork), else lane by lane.
    bool at_once =
        shaded != 0 && (sc.lights.size() <= 1 || depth == 0 || sc.one_ray_per_sample);
    for (std::size_t i = first; i < end && at_once; ++i)
      at_once = (shaded >> (i - first) & 1) || !b.hits[i].found();
    if (at_once) emit_lanes(sc, phong, samples + first, b);
    for (std::size_t i = first; i < end; ++i) {
      if (shaded >> (i - first) & 1) {
        const int l = int(i - first);
        if (at_once)
          b.colors[samples[i]] += phong.ambient(l);
        else
          emit_lane(sc, phong, l, samples[i], b);
        continue;
      }
      if (!b.hits[i].found()) {
        b.colors[samples[i]] +=
            b.rays.weight(i) *
            (sc.has_environment ? sc.environment.radiance(b.rays.ray(i).dir) : sc.background);
        continue;
      }
      const PathRay pr = b.rays[i];
      if (lists) {
        const std::uint32_t k = b.list_of[i];
        shade_hit(sc, st, depth, pr, b.points[i],
                  LightList{b.light_items.data() + b.list_begin[k],
                            b.list_begin[k + 1] - b.list_begin[k], b.list_sees.data() + b.list_begin[k]},
                  pixel_angle, b, counts);
      } else {
        shade_hit(sc, st, depth, pr, surface_at(sc.accel, pr.ray, b.hits[i], sc.offset_scale),
                  LightList{nullptr, sc.lights.size()}, pixel_angle, b, counts);
      }
    }
  }
}

// Stage 4: b.passed[i] = the light that passes along shadow ray i. With packets, the rays
// of each light are traced together (rays to one light from neighbouring points are
// coherent), 16 at a time in batch order; a light with fewer than kMinShadowPacket rays
// (many small lights, each reaching a few points) has them traced one by one.
inline constexpr std::size_t kMinShadowPacket = 4;

// b.by_light: the rays of b.to_trace grouped by light, stable; b.light_begin: the ends of
// the groups. A counting sort over the lights when there are fewer lights than rays, else
// a sort of the rays (whose cost does not grow with the scene's light count).
inline void group_by_light(const CompiledScene& sc, Batches& b) {
  const std::size_t m = b.to_trace.size();
  b.by_light.resize(m);
  b.light_begin.clear();
  const auto light_of = [&b](std::size_t k) { return b.shadows.light(b.to_trace[k]); };
  if (sc.lights.size() <= m) {
    b.light_begin.resize(sc.lights.size() + 1);  // zeros
    for (const std::uint32_t i : b.to_trace) ++b.light_begin[b.shadows.light(i) + 1];
    for (std::size_t l = 1; l < b.light_begin.size(); ++l)
      b.light_begin[l] += b.light_begin[l - 1];
    for (const std::uint32_t i : b.to_trace) b.by_light[b.light_begin[b.shadows.light(i)]++] = i;
    // light_begin[l] is now the end of light l's run.
  } else {
    // Sorted by (light, ray): stable by construction. (A sort of a type of this namespace:
    // std::sort of plain integers would be instantiated here and in the portable code
    // alike, and the linker could keep this instruction set's copy for both.)
    b.light_rays.resize(m);
    for (std::size_t k = 0; k < m; ++k) b.light_rays[k] = {light_of(k), b.to_trace[k]};
    std::sort(b.light_rays.begin(), b.light_rays.end(), [](const LightRay& x, const LightRay& y) {
      return x.light < y.light || (x.light == y.light && x.ray < y.ray);
    });
    for (std::size_t k = 0; k < m; ++k) b.by_light[k] = b.light_rays[k].ray;
    for (std::size_t k = 1; k <= m; ++k)
      if (k == m || b.light_rays[k].light != b.light_rays[k - 1].light)
        b.light_begin.push_back(static_cast<std::uint32_t>(k));
  }
}

template <bool Watertight>
void trace_shadows(const CompiledScene& sc, const RenderSettings& st, Batches& b,
                   TraversalCounts& walk) {
  const std::size_t n = b.shadows.size();
  b.passed.resize(n);
  if (!st.shadows) {
    std::fill(b.passed.begin(), b.passed.end(), 1.0f);
    return;
  }
  const auto one = [&](std::uint32_t i) {
    b.passed[i] = transmittance<Watertight>(sc.accel, sc.materials, b.shadows.ray(i), 0.0f,
                                            b.shadows.distance(i), &walk);
  };
  // Rays proven unoccluded pass whole (what their walk would return); the others are traced
  // (b.to_trace), with packets in groups by light (b.by_light, ending at b.light_begin).
  // A batch with no proven ray whose lights never decrease (one light, say) is its own
  // grouping: its runs, which ShadowRays kept as they were added.
  const bool as_is = b.shadows.grouped() && !b.shadows.some_unoccluded();
  if (as_is) {
    if (!st.packets) {
      for (std::size_t i = 0; i < n; ++i) one(static_cast<std::uint32_t>(i));
      return;
    }
  } else {
    b.to_trace.clear();
    for (std::size_t i = 0; i < n; ++i) {
      if (b.shadows.unoccluded(i))
        b.passed[i] = 1.0f;
      else
        b.to_trace.push_back(static_cast<std::uint32_t>(i));
    }
    if (!st.packets) {
      for (const std::uint32_t i : b.to_trace) one(i);
      return;
    }
    group_by_light(sc, b);
  }
  // Packets of up to 16 rays of a run; in a batch traced as it is, a packet's rays are
  // consecutive and load straight from the columns.
  const auto trace_run = [&](std::size_t run, std::size_t run_end) {
    if (run_end - run < kMinShadowPacket) {
      for (; run < run_end; ++run) one(as_is ? static_cast<std::uint32_t>(run) : b.by_light[run]);
      return;
    }
    for (; run < run_end; run += kPacketSize) {
      const int count = static_cast<int>(std::min<std::size_t>(kPacketSize, run_end - run));
      const PacketMask lanes = (PacketMask(1) << count) - 1;
      if (as_is) {
        transmittance_packet<Watertight>(sc.accel, sc.materials, b.shadows.rays(), run, lanes, 0.0f,
                                         b.shadows.distances() + run, b.passed.data() + run, &walk);
        continue;
      }
      Ray rays[kPacketSize];
      float t_max[kPacketSize], passed[kPacketSize];
      for (int l = 0; l < count; ++l) {
        rays[l] = b.shadows.ray(b.by_light[run + l]);
        t_max[l] = b.shadows.distance(b.by_light[run + l]);
      }
      transmittance_packet<Watertight>(sc.accel, sc.materials, rays, lanes, 0.0f, t_max, passed,
                                       &walk);
      for (int l = 0; l < count; ++l) b.passed[b.by_light[run + l]] = passed[l];
    }
  };
  // The runs: of the batch as it is (ShadowRays kept their ends), or of its groups.
  const std::vector<std::uint32_t>& ends = as_is ? b.shadows.run_ends() : b.light_begin;
  std::size_t run = 0;
  for (const std::uint32_t run_end : ends) {
    trace_run(run, run_end);
    run = run_end;
  }
  if (as_is) trace_run(run, n);
}

// Samples [s0, s1) of the pixels of `block` (at most RenderSettings::block squared), into
// the film, each stage's time added to counts.stages when RenderSettings::stage_times.
template <bool Watertight>
void render_block(const Renderer& r, const Tile& block, int s0, int s1, Film& film,
                  Batches& b, RayCounts& counts) {
  using Clock = std::chrono::steady_clock;
  const bool timed = r.settings().stage_times;
  Clock::time_point t = timed ? Clock::now() : Clock::time_point();
  const auto lap = [&t, timed](std::uint64_t& stage) {
    if (!timed) return;
    const Clock::time_point now = Clock::now();
    stage += static_cast<std::uint64_t>(
        std::chrono::duration_cast<std::chrono::nanoseconds>(now - t).count());
    t = now;
  };
  StageTimes& times = counts.stages;
  const CompiledScene& sc = r.scene();
  const RenderSettings& st = r.settings();
  const bool lists = uses_light_lists(r);
  const int samples = s1 - s0;
  const std::size_t n = std::size_t(block.x1 - block.x0) * std::size_t(block.y1 - block.y0) *
                        std::size_t(samples);
  b.colors.assign(n, vec4());
  film.prefetch(block.x0, block.y0, block.x1, block.y1);  // for step 6
  generate(r, block, s0, s1, b);  // 1.
  counts.primary += n;
  lap(times.generate);
  for (int depth = 0; !b.rays.empty(); ++depth) {
    const bool primary = depth == 0;
    b.next.clear();
    b.shadows.clear();
    // 2. intersect: the primary batch in its packets, the others 16 rays at a time
    b.hits.resize(b.rays.size());
    if (primary) {
      for (std::size_t k = 0; k + 1 < b.packet_begin.size(); ++k)
        intersect<Watertight>(sc, st, b.packet_begin[k], b.packet_begin[k + 1], b,
                              counts.primary_walk);
    } else {
      for (std::size_t i = 0; i < b.rays.size(); i += kPacketSize)
        intersect<Watertight>(sc, st, i, std::min(i + kPacketSize, b.rays.size()), b,
                              counts.secondary_walk);
    }
    lap(times.intersect);
    // 3. shade: surface points, their lights, the terms and the next batch
    if (lists) {
      surface_points(sc, b);
      lap(times.shade);
      find_lights(r, primary, b, counts.lights);
      lap(times.lights);
    }
    shade_hits(r, lists, depth, b, counts);
    lap(times.shade);
    // 4. shadows, each sample's terms added in batch order
    trace_shadows<Watertight>(sc, st, b, counts.shadow_walk);
    for (std::size_t i = 0; i < b.shadows.size(); ++i)
      if (b.passed[i] != 0.0f) b.colors[b.shadows.sample(i)] += b.shadows.term(i) * b.passed[i];
    lap(times.shadow);
    // 5. next depth
    std::swap(b.rays, b.next);
  }
  // 6. film, samples in index order
  std::size_t i = 0;
  for (int y = block.y0; y < block.y1; ++y)
    for (int x = block.x0; x < block.x1; ++x)
      for (int k = 0; k < samples; ++k) film.add(x, y, b.colors[i++]);
  lap(times.shade);
}

}  // namespace detail

// Samples [s0, s1) of the pixels of `tile`, block by block, into the film.
template <bool Watertight>
void render_tile_kernel(const Renderer& r, const Tile& tile, int s0, int s1, Film& film,
                        RayCounts& counts) {
  static thread_local detail::Batches batches;
  const int side = r.settings().block;
  RayCounts local;
  for (int y = tile.y0; y < tile.y1; y += side)
    for (int x = tile.x0; x < tile.x1; x += side) {
      const Tile block{x, y, std::min(x + side, tile.x1), std::min(y + side, tile.y1)};
      detail::render_block<Watertight>(r, block, s0, s1, film, batches, local);
    }
  counts += local;
}

}  // namespace rt2::RT2_ISA
