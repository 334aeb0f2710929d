// tests/bench/embree_runner.h — Embree 3 for bench_trace: a device, a scene over the same
// mesh arrays rt2 reads, and runners for rtcIntersect1 / rtcOccluded1 per ray and
// rtcIntersect16 / rtcOccluded16 per 4 x 4 tile. Included only when RT2_HAVE_EMBREE is
// defined (SCons found Debian's libembree-dev); nothing else in rt2 uses Embree.
#pragma once

#include <embree3/rtcore.h>

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "rt2/scene/instance.h"
#include "rt2/scene/mesh.h"
#include "tests/bench/trace_runner.h"

namespace bench {

using rt2::kInfinity;
using rt2::vec4;

inline void embree_error(void*, RTCError code, const char* message) {
  std::fprintf(stderr, "bench_trace: embree error %d: %s\n", int(code), message ? message : "");
  std::exit(1);
}

// Net bytes Embree allocated on the device since the last reset (frees are negative).
inline std::atomic<long long> g_embree_bytes{0};

inline bool embree_memory(void*, ssize_t bytes, bool) {
  g_embree_bytes += bytes;
  return true;
}

inline RTCDevice embree_device(const char* config) {
  RTCDevice dev = rtcNewDevice(config);
  if (!dev) {
    std::fprintf(stderr, "bench_trace: rtcNewDevice(\"%s\") failed (error %d)\n",
                 config ? config : "", int(rtcGetDeviceError(nullptr)));
    std::exit(1);
  }
  rtcSetDeviceErrorFunction(dev, embree_error, nullptr);
  rtcSetDeviceMemoryMonitorFunction(dev, embree_memory, nullptr);
  return dev;
}

// The scene, not yet committed: one triangle geometry on the mesh's own arrays.
inline RTCScene embree_scene(RTCDevice dev, const rt2::Mesh& mesh, bool robust) {
  RTCScene scene = rtcNewScene(dev);
  rtcSetSceneFlags(scene, robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_MEDIUM);
  RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_MEDIUM);
  // vec4 positions: a float3 every 16 bytes, so Embree's 16-byte loads stay inside.
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                             mesh.positions.data(), 0, sizeof(vec4), mesh.positions.size());
  static_assert(sizeof(mesh.faces[0]) == 3 * sizeof(std::uint32_t));
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh.faces.data(),
                             0, sizeof(mesh.faces[0]), mesh.faces.size());
  rtcCommitGeometry(g);
  rtcAttachGeometry(scene, g);
  rtcReleaseGeometry(g);
  return scene;
}

// A top scene holding `mesh_scene` (committed) as one instance placed by `in`, committed,
// with the flags of embree_scene; the top scene holds the only reference to `mesh_scene`.
inline RTCScene embree_instance_of(RTCDevice dev, RTCScene mesh_scene, const rt2::Instance& in,
                                   bool robust) {
  RTCScene top = rtcNewScene(dev);
  rtcSetSceneFlags(top, robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
  rtcSetSceneBuildQuality(top, RTC_BUILD_QUALITY_MEDIUM);
  RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(g, mesh_scene);
  float xfm[12];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) xfm[r * 4 + c] = float(in.to_world.m[std::size_t(r)][std::size_t(c)]);
  rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, xfm);
  rtcCommitGeometry(g);
  rtcAttachGeometry(top, g);
  rtcReleaseGeometry(g);
  rtcReleaseScene(mesh_scene);
  rtcCommitScene(top);
  return top;
}

inline Hit from_embree(const RTCRayHit& rh) {
  Hit h;
  if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
    h.t = rh.ray.tfar;
    h.u = rh.hit.u;
    h.v = rh.hit.v;
    h.prim = rh.hit.primID;  // Embree's face index: not comparable with rt2's
  }
  return h;
}

inline void to_embree(const Ray& r, float t_max, RTCRay& e) {
  e.org_x = r.org[0];
  e.org_y = r.org[1];
  e.org_z = r.org[2];
  e.tnear = 0.0f;
  e.dir_x = r.dir[0];
  e.dir_y = r.dir[1];
  e.dir_z = r.dir[2];
  e.time = 0.0f;
  e.tfar = t_max;
  e.mask = ~0u;
  e.id = 0;
  e.flags = 0;
}

inline Hit embree_closest_one(RTCScene scene, const Ray& r, float t_max) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  to_embree(r, t_max, rh.ray);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene, &ctx, &rh);
  return from_embree(rh);
}

inline Runner embree1_runner(RTCScene scene, const RaySet& set, std::size_t chunk) {
  Runner r;
  r.engine = "embree";
  r.units = set.size();
  r.chunk = chunk;
  if (set.occlusion) {
    r.answers.occluded.resize(set.size());
    r.body = [scene, &set, out = r.answers.occluded.data()](std::size_t b, std::size_t e) {
      RTCIntersectContext ctx;
      rtcInitIntersectContext(&ctx);
      for (std::size_t i = b; i < e; ++i) {
        RTCRay ray;
        to_embree(set.rays[i], set.t_max[i], ray);
        rtcOccluded1(scene, &ctx, &ray);
        out[i] = ray.tfar == -kInfinity;
      }
    };
  } else {
    r.answers.hits.resize(set.size());
    r.body = [scene, &set, out = r.answers.hits.data()](std::size_t b, std::size_t e) {
      RTCIntersectContext ctx;
      rtcInitIntersectContext(&ctx);
      for (std::size_t i = b; i < e; ++i) {
        RTCRayHit rh;
        to_embree(set.rays[i], set.t_max[i], rh.ray);
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &ctx, &rh);
        out[i] = from_embree(rh);
      }
    };
  }
  r.closest_one = [scene, &set](std::size_t i) {
    return embree_closest_one(scene, set.rays[i], set.t_max[i]);
  };
  return r;
}

// Lane `l` of a 16-ray packet from a ray (RTCRay16 and the ray part of RTCRayHit16 share
// this layout).
template <class P>
inline void set_lane(P& p, int l, const Ray& r, float t_max) {
  p.org_x[l] = r.org[0];
  p.org_y[l] = r.org[1];
  p.org_z[l] = r.org[2];
  p.tnear[l] = 0.0f;
  p.dir_x[l] = r.dir[0];
  p.dir_y[l] = r.dir[1];
  p.dir_z[l] = r.dir[2];
  p.time[l] = 0.0f;
  p.tfar[l] = t_max;
  p.mask[l] = ~0u;
  p.id[l] = 0;
  p.flags[l] = 0;
}

inline Runner embree16_runner(RTCScene scene, const RaySet& set, std::size_t chunk) {
  Runner r;
  r.engine = "embree16";
  r.units = set.tiles();
  r.chunk = std::max<std::size_t>(1, chunk / 16);
  const Ray idle(vec4(0.0f, 0.0f, 0.0f), vec4(0.0f, 0.0f, 1.0f));
  if (set.occlusion) {
    r.answers.occluded.resize(set.size());
    r.body = [scene, &set, idle, out = r.answers.occluded.data()](std::size_t b, std::size_t e) {
      RTCIntersectContext ctx;
      rtcInitIntersectContext(&ctx);
      ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      for (std::size_t t = b; t < e; ++t) {
        alignas(64) int valid[16];
        RTCRay16 p;
        for (int l = 0; l < 16; ++l) {
          valid[l] = 0;
          set_lane(p, l, idle, -kInfinity);
        }
        for (std::uint32_t i = set.tile_begin[t]; i < set.tile_begin[t + 1]; ++i) {
          valid[set.lane[i]] = -1;
          set_lane(p, set.lane[i], set.rays[i], set.t_max[i]);
        }
        rtcOccluded16(valid, scene, &ctx, &p);
        for (std::uint32_t i = set.tile_begin[t]; i < set.tile_begin[t + 1]; ++i)
          out[i] = p.tfar[set.lane[i]] == -kInfinity;
      }
    };
  } else {
    r.answers.hits.resize(set.size());
    r.body = [scene, &set, idle, out = r.answers.hits.data()](std::size_t b, std::size_t e) {
      RTCIntersectContext ctx;
      rtcInitIntersectContext(&ctx);
      ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      for (std::size_t t = b; t < e; ++t) {
        alignas(64) int valid[16];
        RTCRayHit16 p;
        for (int l = 0; l < 16; ++l) {
          valid[l] = 0;
          set_lane(p.ray, l, idle, -kInfinity);
          p.hit.geomID[l] = RTC_INVALID_GEOMETRY_ID;
          p.hit.instID[0][l] = RTC_INVALID_GEOMETRY_ID;
        }
        for (std::uint32_t i = set.tile_begin[t]; i < set.tile_begin[t + 1]; ++i) {
          valid[set.lane[i]] = -1;
          set_lane(p.ray, set.lane[i], set.rays[i], set.t_max[i]);
        }
        rtcIntersect16(valid, scene, &ctx, &p);
        for (std::uint32_t i = set.tile_begin[t]; i < set.tile_begin[t + 1]; ++i) {
          const int l = set.lane[i];
          Hit h;
          if (p.hit.geomID[l] != RTC_INVALID_GEOMETRY_ID) {
            h.t = p.ray.tfar[l];
            h.u = p.hit.u[l];
            h.v = p.hit.v[l];
            h.prim = p.hit.primID[l];
          }
          out[i] = h;
        }
      }
    };
  }
  r.closest_one = [scene, &set](std::size_t i) {
    return embree_closest_one(scene, set.rays[i], set.t_max[i]);
  };
  return r;
}

}  // namespace bench
