// rt2/tracer.h — the render kernel: Whitted ray tracing with Phong shading (thesis 3.1,
// 3.2) over batches of rays, as a template over the triangle test.
//
// A tile is traced in blocks of pixels (RenderSettings::block). For a block and a range of
// samples the kernel runs stages over batches, breadth first through the ray tree:
//   1. generate: one primary ray per sample of every pixel of the block, in packets of one
//      sample over 4 x 4 pixels;
//   2. intersect the batch (closest hit), packet by packet (secondary batches 16 rays at a
//      time, in batch order): rt2/query.h's packet queries, or one ray at a time when
//      RenderSettings::packets is off, with the same answers;
//   3. shade the hits: their surface points; the lights each point considers (all of
//      them, or a list from light culling: per block or per depth slice of a block for
//      primary hits, from a walk of the light tree for the others; RenderSettings::
//      light_culling); the ambient term goes to the sample's colour at once; for each of
//      those lights in range that the surface faces, the unshadowed Phong term goes into a
//      batch of shadow rays; reflected and refracted rays whose weight passes min_weight go
//      into the next batch;
//   4. trace the shadow batch (transmittance; in packets of 16 rays to one light, grouped by
//      a stable sort) and add each light's term times what passed, in batch order; a ray
//      from a tile or cluster to a light it provably sees whole (cluster_visibility.h) is
//      not traced: it passes 1, as its walk would return;
//   5. repeat 2 ... 4 with the next batch until it is empty or `depth` is reached;
//   6. add each sample's colour to the film, samples in index order.
// A ray's contribution is its weight (the product of the Kr / Kt factors along its path)
// times the local colour where it lands, as before; only the order in which a sample's
// terms are summed follows the stages (so images differ from the depth-first renderer of
// rt2 0.2 by rounding, RMSE below 1e-7 on the shipped scenes). Every sample is computed on
// its own, so the batches' sizes never change a pixel.
//
// Compiled per instruction set (rt2/isa.h) by isa_kernels.cpp: the code lives in
// rt2::RT2_ISA. Materials decide reflection, refraction and highlights at run time (a
// kernel compiled per combination of scene features measured about 1 % faster, inside the
// noise, so it was dropped).
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "rt2/cluster_visibility.h"
#include "rt2/offset.h"
#include "rt2/optics.h"
#include "rt2/query.h"
#include "rt2/render.h"

namespace rt2::RT2_ISA {
namespace detail {

// A ray of the ray tree, and whose sample it adds to.
struct PathRay {
  Ray ray;
  float weight;      // product of Kr / Kt along the path
  std::uint32_t sample;  // index into the block's sample colours
  int depth;
  RayKind kind;
};

// A shadow ray, with the light's unshadowed term at the point it leaves.
struct ShadowRay {
  Ray ray;
  vec4 term;  // weight x (Kd (L·N) + Ks (R·V)^n) x light radiance
  float distance;
  std::uint32_t sample;
  std::uint32_t light;  // index into CompiledScene::lights
  bool unoccluded;      // proven to pass whole (cluster_visibility.h): not traced
};

// What shading needs to know about a hit.
struct SurfacePoint {
  vec4 p;                   // on the surface, computed precisely (see offset.h)
  vec4 ng;                  // unit geometric normal, on the side the ray came from
  vec4 ns;                  // unit shading normal, same side
  vec4 above;               // p moved off the surface along ng: where shadow and reflected
                            // rays start (offset.h)
  bool entering;            // the ray hit the outside (against the outward normal)
  std::uint32_t material;
};

// The lights a shading point considers: CompiledScene::lights[index[k]] for k < count, or
// every light (index null, count = all).
struct LightList {
  const std::uint32_t* index = nullptr;
  std::size_t count = 0;
  // Per light of the list, whether every shadow ray from the list's cluster to it provably
  // meets nothing (cluster_visibility.h); null: nothing proven.
  const std::uint8_t* sees = nullptr;
  std::uint32_t operator[](std::size_t k) const {
    return index ? index[k] : static_cast<std::uint32_t>(k);
  }
};

// A shadow ray's light and its index in the batch, for grouping the batch by light.
struct LightRay {
  std::uint32_t light, ray;
};

// The batches of one thread, reused from block to block (no allocation once grown).
struct Batches {
  std::vector<PathRay> rays, next;
  std::vector<std::uint32_t> packet_begin;  // the primary batch's packets (generate)
  std::vector<Hit> hits;                    // per ray of `rays`
  std::vector<SurfacePoint> points;         // per ray of `rays` that hit
  // Light lists: list k is light_items[list_begin[k], list_begin[k + 1]); the hit of ray
  // i uses list list_of[i]. No lists: every hit considers every light.
  std::vector<std::uint32_t> light_items, list_begin, list_of;
  std::vector<std::uint8_t> list_sees;  // parallel to light_items (see LightList::sees)
  ClusterVisibility visibility;
  std::vector<std::uint32_t> to_trace;  // the shadow rays to trace
  std::vector<std::uint32_t> found;     // one query's answer
  std::vector<float> depth;             // clustered culling: per ray, its hit's depth
  std::vector<Aabb> cluster_bounds;     // clustered culling: per slice
  std::vector<ShadowRay> shadows;
  std::vector<float> passed;              // per shadow ray: the light that passes
  std::vector<std::uint32_t> by_light;    // shadow rays grouped by light, in batch order
  std::vector<std::uint32_t> light_begin;
  std::vector<LightRay> light_rays;
  std::vector<vec4> colors;
};

inline SurfacePoint surface_at(const Accel& acc, const Ray& ray, const Hit& h,
                               float offset_scale) {
  SurfacePoint s;
  const std::uint32_t i = prim_index(h.prim);
  if (prim_tag(h.prim) == kTriangleTag) {
    const Triangle& tri = acc.tris[i];
    s.p = tri.point(h.u, h.v);  // from barycentrics: precise, see offset.h
    s.ng = normalize(tri.n);
    if (acc.tri_normals.empty()) {
      s.ns = s.ng;
    } else {
      const auto& n = acc.tri_normals[i];
      s.ns = normalize((1.0f - h.u - h.v) * n[0] + h.u * n[1] + h.v * n[2]);
    }
  } else if (prim_tag(h.prim) == kSphereTag) {
    const Sphere& sp = acc.spheres[i];
    s.ng = sphere_normal(sp, ray.at(h.t));
    s.p = sp.center + s.ng * sp.radius;  // re-projected onto the surface
    s.ns = s.ng;
  } else {
    const Plane& pl = acc.planes[i];
    const vec4 q = ray.at(h.t);
    s.p = q - pl.n * (float(dot(q, pl.n)) + pl.d);  // projected onto the plane
    s.ng = s.ns = pl.n;
  }
  s.material = acc.material_of(h.prim);
  s.entering = dot(ray.dir, s.ng) < 0.0f;
  if (!s.entering) {
    s.ng = -s.ng;
    s.ns = -s.ns;
  }
  if (!(dot(s.ns, ray.dir) < 0.0f)) s.ns = s.ng;  // an interpolated normal facing away
  s.above = offset_ray_origin(s.p, s.ng, offset_scale);
  return s;
}

// Stage 3 for one hit: I_local = Ka I_amb now, and for each light of `lights` in range
// that reaches the surface the term Kd I (L·N) + Ks I (R·V)^n (times the light's range
// window, light.h) into the shadow batch, to be scaled by what passes (thesis 3.2; SPEC
// "Shading"). `lights` holds every light in range, in scene order, whatever the culling.
inline void shade(const CompiledScene& sc, const PathRay& r, const SurfacePoint& s,
                  LightList lights, Batches& b, RayCounts& counts) {
  const Material& m = sc.materials[s.material];
  b.colors[r.sample] += r.weight * (m.ambient * sc.ambient);
  ++counts.lights.points;
  counts.lights.considered += lights.count;
  if (lights.count == 0) return;
  const vec4 kd = m.diffuse_at(s.p + sc.origin);  // textures live in world coordinates
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
    // Written field by field: a whole temporary copied in would be read back as one wide
    // load from narrower stores (a store-forwarding stall, 14 % of a frame).
    ShadowRay& sr = b.shadows.emplace_back();
    sr.ray.org = origin;
    sr.ray.dir = l;
    sr.term = r.weight * (term * (light.has_range() ? light.radiance() * range_window(light, dist)
                                                    : light.radiance()));
    sr.distance = dist;
    sr.sample = r.sample;
    sr.light = li;
    sr.unoccluded = unoccluded;
  }
}

// Appends a child of `parent` to the next batch, field by field (see shade).
MLIB_INLINE void push_path_ray(Batches& b, const vec4& org, const vec4& dir, float weight,
                               const PathRay& parent, RayKind kind) {
  PathRay& pr = b.next.emplace_back();
  pr.ray.org = org;
  pr.ray.dir = dir;
  pr.weight = weight;
  pr.sample = parent.sample;
  pr.depth = parent.depth + 1;
  pr.kind = kind;
}

// Stage 3's secondary rays: refraction (or, on total internal reflection, its share
// reflected) and reflection, when deep and heavy enough.
inline void spawn(const CompiledScene& sc, const RenderSettings& st, const PathRay& r,
                  const SurfacePoint& s, Batches& b) {
  if (r.depth >= st.depth) return;
  const Material& m = sc.materials[s.material];
  if (m.transparency > 0.0f) {
    const float w = r.weight * m.transparency;
    if (w > st.min_weight) {
      const float eta = s.entering ? 1.0f / m.ior : m.ior;
      vec4 t;
      if (refract(r.ray.dir, s.ns, eta, t))
        push_path_ray(b, offset_ray_origin(s.p, -s.ng, sc.offset_scale), t, w, r,
                      RayKind::refraction);
      else  // total internal reflection: the transmitted share is reflected
        push_path_ray(b, s.above, reflect(r.ray.dir, s.ns), w, r, RayKind::reflection);
    }
  }
  if (m.reflectivity > 0.0f) {
    const float w = r.weight * m.reflectivity;
    if (w > st.min_weight)
      push_path_ray(b, s.above, reflect(r.ray.dir, s.ns), w, r, RayKind::reflection);
  }
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
  b.packet_begin.assign(1, 0);
  for (int gy = block.y0; gy < block.y1; gy += 4)
    for (int gx = block.x0; gx < block.x1; gx += 4)
      for (int k = s0; k < s1; ++k) {
        const SubpixelOffset& o = offsets[k];
        for (int y = gy; y < std::min(gy + 4, block.y1); ++y)
          for (int x = gx; x < std::min(gx + 4, block.x1); ++x) {
            PathRay& pr = b.rays.emplace_back();
            pr.ray = cam.ray(float(x) + o.x, float(y) + o.y, st.width, st.height);
            pr.weight = 1.0f;
            pr.sample = static_cast<std::uint32_t>(((y - block.y0) * bw + x - block.x0) * samples +
                                                   k - s0);
            pr.depth = 0;
            pr.kind = RayKind::primary;
          }
        b.packet_begin.push_back(static_cast<std::uint32_t>(b.rays.size()));
      }
}

// Stage 2 for rays [begin, end) of b.rays (at most kPacketSize): b.hits[i] = the closest
// hit of ray i, found as one packet or one ray at a time.
template <bool Watertight>
void intersect(const CompiledScene& sc, const RenderSettings& st, std::size_t begin,
               std::size_t end, Batches& b, TraversalCounts& walk) {
  Ray rays[kPacketSize];
  float t_max[kPacketSize];
  Hit* hits = b.hits.data() + begin;
  const int n = static_cast<int>(end - begin);
  for (int l = 0; l < n; ++l) {
    rays[l] = b.rays[begin + l].ray;
    t_max[l] = kInfinity;
  }
  if (st.packets) {
    closest_hit_packet<Watertight>(sc.accel, rays, (PacketMask(1) << n) - 1, 0.0f, t_max, hits,
                                   &walk);
  } else {
    for (int l = 0; l < n; ++l)
      hits[l] = closest_hit<Watertight>(sc.accel, rays[l], 0.0f, kInfinity, &walk);
  }
}

// Stage 3, first step: the surface point of every hit of the batch.
inline void surface_points(const CompiledScene& sc, Batches& b) {
  const std::size_t n = b.rays.size();
  b.points.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    if (b.hits[i].found())
      b.points[i] = surface_at(sc.accel, b.rays[i].ray, b.hits[i], sc.offset_scale);
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
  b.list_begin.assign(1, 0);
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

// Stage 3, last step: each hit shaded with its lights and its secondary rays spawned; a
// miss takes the background. With lists, the surface points are b.points (the first step
// made them, the second used them); without, every hit considers every light and its
// surface point is made here (the first two steps are skipped: one pass over the hits).
inline void shade_hits(const Renderer& r, bool lists, Batches& b, RayCounts& counts) {
  const CompiledScene& sc = r.scene();
  for (std::size_t i = 0; i < b.rays.size(); ++i) {
    const PathRay& pr = b.rays[i];
    counts.reflection += pr.kind == RayKind::reflection;
    counts.refraction += pr.kind == RayKind::refraction;
    if (!b.hits[i].found()) {
      b.colors[pr.sample] += pr.weight * sc.background;
      continue;
    }
    if (lists) {
      const std::uint32_t k = b.list_of[i];
      const LightList lights{b.light_items.data() + b.list_begin[k],
                             b.list_begin[k + 1] - b.list_begin[k],
                             b.list_sees.data() + b.list_begin[k]};
      shade(sc, pr, b.points[i], lights, b, counts);
      spawn(sc, r.settings(), pr, b.points[i], b);
    } else {
      const SurfacePoint s = surface_at(sc.accel, pr.ray, b.hits[i], sc.offset_scale);
      shade(sc, pr, s, LightList{nullptr, sc.lights.size()}, b, counts);
      spawn(sc, r.settings(), pr, s, b);
    }
  }
}

// Stage 4: b.passed[i] = the light that passes along shadow ray i. With packets, the rays
// of each light are traced together (rays to one light from neighbouring points are
// coherent), 16 at a time in batch order; a light with fewer than kMinShadowPacket rays
// (many small lights, each reaching a few points) has them traced one by one.
inline constexpr std::size_t kMinShadowPacket = 4;

template <bool Watertight>
void trace_shadows(const CompiledScene& sc, const RenderSettings& st, Batches& b,
                   TraversalCounts& walk) {
  const std::size_t n = b.shadows.size();
  b.passed.resize(n);
  if (!st.shadows) {
    std::fill(b.passed.begin(), b.passed.end(), 1.0f);
    return;
  }
  // Rays proven unoccluded pass whole (what their walk would return); the others are traced.
  b.to_trace.clear();
  for (std::size_t i = 0; i < n; ++i) {
    if (b.shadows[i].unoccluded)
      b.passed[i] = 1.0f;
    else
      b.to_trace.push_back(static_cast<std::uint32_t>(i));
  }
  const std::size_t m = b.to_trace.size();
  const auto one = [&](std::uint32_t i) {
    b.passed[i] = transmittance<Watertight>(sc.accel, sc.materials, b.shadows[i].ray, 0.0f,
                                            b.shadows[i].distance, &walk);
  };
  if (!st.packets) {
    for (const std::uint32_t i : b.to_trace) one(i);
    return;
  }
  // b.by_light: the rays to trace grouped by light, stable; b.light_begin: the ends of the
  // groups. A counting sort over the lights when there are fewer lights than rays, else a
  // sort of the rays (whose cost does not grow with the scene's light count).
  b.by_light.resize(m);
  b.light_begin.clear();
  if (sc.lights.size() <= m) {
    b.light_begin.assign(sc.lights.size() + 1, 0);
    for (const std::uint32_t i : b.to_trace) ++b.light_begin[b.shadows[i].light + 1];
    for (std::size_t l = 1; l < b.light_begin.size(); ++l)
      b.light_begin[l] += b.light_begin[l - 1];
    for (const std::uint32_t i : b.to_trace) b.by_light[b.light_begin[b.shadows[i].light]++] = i;
    // light_begin[l] is now the end of light l's run.
  } else {
    // Sorted by (light, ray): stable by construction. (A sort of a type of this namespace:
    // std::sort of plain integers would be instantiated here and in the portable code
    // alike, and the linker could keep this instruction set's copy for both.)
    b.light_rays.resize(m);
    for (std::size_t k = 0; k < m; ++k)
      b.light_rays[k] = {b.shadows[b.to_trace[k]].light, b.to_trace[k]};
    std::sort(b.light_rays.begin(), b.light_rays.end(), [](const LightRay& x, const LightRay& y) {
      return x.light < y.light || (x.light == y.light && x.ray < y.ray);
    });
    for (std::size_t k = 0; k < m; ++k) b.by_light[k] = b.light_rays[k].ray;
    for (std::size_t k = 1; k <= m; ++k)
      if (k == m || b.light_rays[k].light != b.light_rays[k - 1].light)
        b.light_begin.push_back(static_cast<std::uint32_t>(k));
  }
  std::size_t run = 0;
  for (const std::uint32_t run_end : b.light_begin) {
    if (run_end - run < kMinShadowPacket) {
      for (; run < run_end; ++run) one(b.by_light[run]);
      continue;
    }
    for (; run < run_end; run += kPacketSize) {
      const int count = static_cast<int>(std::min<std::size_t>(kPacketSize, run_end - run));
      Ray rays[kPacketSize];
      float t_max[kPacketSize], passed[kPacketSize];
      for (int l = 0; l < count; ++l) {
        const ShadowRay& sr = b.shadows[b.by_light[run + l]];
        rays[l] = sr.ray;
        t_max[l] = sr.distance;
      }
      transmittance_packet<Watertight>(sc.accel, sc.materials, rays,
                                       (PacketMask(1) << count) - 1, 0.0f, t_max, passed, &walk);
      for (int l = 0; l < count; ++l) b.passed[b.by_light[run + l]] = passed[l];
    }
    run = run_end;
  }
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
  for (bool primary = true; !b.rays.empty(); primary = false) {
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
    shade_hits(r, lists, b, counts);
    lap(times.shade);
    // 4. shadows, each sample's terms added in batch order
    trace_shadows<Watertight>(sc, st, b, counts.shadow_walk);
    for (std::size_t i = 0; i < b.shadows.size(); ++i)
      if (b.passed[i] != 0.0f) b.colors[b.shadows[i].sample] += b.shadows[i].term * b.passed[i];
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
