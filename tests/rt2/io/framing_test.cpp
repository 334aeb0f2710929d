// tests/rt2/io/framing_test.cpp — the camera and light of a file that brings none
// (rt2/io/framing.h): the whole box in view at any aspect, never edge-on, the ground below.
//
// Boxes of many shapes (a cube, flat ones along each axis, rods, and log-uniform random ones
// with a fixed seed) are framed for images of 4:3, 16:9, 1:3 and 3:1.
#include "rt2/io/framing.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "rt2/io/scene_io.h"
#include "tests/rt2/temp_dir.h"

namespace rt2::io {
namespace {

Aabb box(float x0, float y0, float z0, float x1, float y1, float z1) {
  Aabb b;
  b.grow(vec4(x0, y0, z0));
  b.grow(vec4(x1, y1, z1));
  return b;
}

std::string str(const Aabb& b) {
  std::string s;
  for (const vec4* v : {&b.lo, &b.hi})
    s += (s.empty() ? "(" : " .. (") + std::to_string((*v)[0]) + ", " + std::to_string((*v)[1]) +
         ", " + std::to_string((*v)[2]) + ")";
  return s;
}

vec4 corner(const Aabb& b, int i) {
  return vec4((i & 1 ? b.hi : b.lo)[0], (i & 2 ? b.hi : b.lo)[1], (i & 4 ? b.hi : b.lo)[2]);
}

// A cube, boxes flat along each axis (one of zero thickness), rods along each axis, and
// random boxes with extents from 1e-3 to 1e3 per axis, away from the origin.
std::vector<Aabb> shapes() {
  std::vector<Aabb> s = {
      box(-1, -1, -1, 1, 1, 1),           box(-4, -1, -0.05f, 4, 1, 0.05f),
      box(-1, 0, -1, 1, 0.01f, 1),        box(-1, 0, -1, 1, 0, 1),
      box(0, -1, -1, 0.01f, 1, 1),        box(-0.1f, 0, -0.1f, 0.1f, 5, 0.1f),
      box(-10, -0.1f, -0.1f, 10, 0.1f, 0.1f), box(-0.1f, -0.1f, -10, 0.1f, 0.1f, 10),
      box(2, 3, 4, 2.5f, 3.01f, 9)};
  std::mt19937 rng(37);
  std::uniform_real_distribution<float> exponent(-3.0f, 3.0f), offset(-10.0f, 10.0f);
  for (int i = 0; i < 200; ++i) {
    const vec4 e(std::pow(10.0f, exponent(rng)), std::pow(10.0f, exponent(rng)),
                 std::pow(10.0f, exponent(rng)));
    const float scale = std::max({e[0], e[1], e[2]});
    const vec4 lo(offset(rng) * scale, offset(rng) * scale, offset(rng) * scale);
    s.push_back(box(lo[0], lo[1], lo[2], lo[0] + e[0], lo[1] + e[1], lo[2] + e[2]));
  }
  return s;
}

const float kAspects[] = {4.0f / 3.0f, 16.0f / 9.0f, 1.0f / 3.0f, 3.0f};

float tan_half(const Camera& c) {
  return std::tan(0.5f * c.fov() * std::numbers::pi_v<float> / 180.0f);
}

TEST(Framing, EveryCornerOfTheBoundsProjectsInsideTheImageAtEveryAspect) {
  for (const Aabb& b : shapes()) {
    const Framing f = framing_of("t.obj", b, "mesh");
    for (const float aspect : kAspects) {
      const Camera c = framing_camera(f, aspect);
      const float th = tan_half(c);
      for (int i = 0; i < 8; ++i) {
        // Image coordinates in [-1, 1] (rt2/scene/camera.h): x / (aspect tan), y / tan.
        const vec4 v = corner(b, i) - c.position();
        const float z = dot(v, c.forward());
        ASSERT_GT(z, 0.0f) << "behind the camera, aspect " << aspect;
        EXPECT_LE(std::fabs(float(dot(v, c.right())) / z) / (aspect * th), 1.0f)
            << "corner " << i << " of " << str(b) << ", aspect " << aspect;
        EXPECT_LE(std::fabs(float(dot(v, c.up())) / z) / th, 1.0f)
            << "corner " << i << " of " << str(b) << ", aspect " << aspect;
      }
    }
  }
}

TEST(Framing, TheViewIsAtLeast20DegreesFromEveryFacePlaneOfTheBox) {
  const float least = std::sin(20.0f * std::numbers::pi_v<float> / 180.0f);
  for (const Aabb& b : shapes()) {
    const Camera c = framing_camera(framing_of("t.obj", b, "mesh"), 16.0f / 9.0f);
    for (std::size_t axis = 0; axis < 3; ++axis)  // the angle to the plane normal to `axis`
      EXPECT_GE(std::fabs(c.forward()[axis]), least)
          << "axis " << axis << " of " << str(b);
  }
}

TEST(Framing, AFlatBoxIsSeenMostNearlyHeadOnThroughItsLargestFace) {
  const Aabb flat[] = {box(0, -1, -1, 0.01f, 1, 1), box(-1, 0, -1, 1, 0.01f, 1),
                       box(-1, -1, 0, 1, 1, 0.01f)};
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const vec4 d = framing_direction(framing_of("t.obj", flat[axis], "mesh"));
    for (std::size_t other = 0; other < 3; ++other) {
      if (other == axis) continue;
      EXPECT_GT(d[axis], d[other] + 0.3f) << axis;
    }
  }
}

TEST(Framing, AFlatModelLyingInXzIsLookedDownAt) {
  for (const Aabb& b : {box(-1, 0, -1, 1, 0.01f, 1), box(-1, 0, -1, 1, 0, 1)}) {
    for (const float aspect : kAspects) {
      const Camera c = framing_camera(framing_of("t.obj", b, "mesh"), aspect);
      EXPECT_GT(c.position()[1], b.hi[1]);
      // At least 45 degrees below the horizon.
      EXPECT_LT(c.forward()[1], -std::sqrt(0.5f)) << aspect;
    }
  }
}

TEST(Framing, TheGroundPlaneStaysUnderTheModelAndTheCameraAndLightAbove) {
  const test::TempDir dir("framing");
  const std::string objs[] = {
      dir.write("cube.obj", "v -1 -1 -1\nv 1 -1 -1\nv 1 1 1\nv -1 1 1\nf 1 2 3 4\n"),
      dir.write("flat.obj", "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nf 1 4 3 2\n"),
      dir.write("wall.obj", "v -4 0 0\nv 4 0 0\nv 4 1 0\nv -4 1 0\nf 1 2 3 4\n"),
      dir.write("tall.obj", "v 0 0 0\nv 0.1 0 0\nv 0.1 9 0.1\nf 1 2 3\n")};
  for (const std::string& obj : objs) {
    Scene s = frame_obj(obj);
    ASSERT_EQ(s.planes.size(), 1u);
    ASSERT_TRUE(s.framed_bounds.has_value());
    const Aabb b = s.meshes.at(0).bounds();
    // The plane n·X + d = 0 with n = +y: y = -d.
    const float ground = -s.planes[0].d;
    EXPECT_LT(ground, b.lo[1]) << obj;
    EXPECT_GT(s.lights.at(0).position[1], b.hi[1]) << obj;
    for (const float aspect : kAspects) {
      fit_framed_camera(s, int(aspect * 300.0f), 300);
      EXPECT_GT(s.camera.position()[1], ground) << obj << " at " << aspect;
      EXPECT_LT(s.camera.forward()[1], 0.0f) << obj << " at " << aspect;  // looks down
    }
  }
}

TEST(Framing, TheLightIsAboveTheModelOnTheCamerasSide) {
  for (const Aabb& b : shapes()) {
    const Framing f = framing_of("t.obj", b, "mesh");
    const vec4 to_light = framing_light(f).position - f.center;
    EXPECT_GT(framing_light(f).position[1], b.hi[1]);
    EXPECT_GT(float(dot(to_light, framing_direction(f))), 0.0f);
  }
}

TEST(Framing, OnlyAFramedCameraIsFittedToTheImage) {
  const test::TempDir dir("framing");
  Scene own = load_scene(dir.write("s.toml", "[camera]\nposition = [0, 1, 5]\nlook_at = [0, 1, 0]\n"
                                             "[materials.m]\n[[spheres]]\ncenter = [0, 0, 0]\n"
                                             "radius = 1\nmaterial = \"m\"\n"));
  EXPECT_FALSE(own.framed_bounds.has_value());
  const Camera before = own.camera;
  fit_framed_camera(own, 100, 300);
  EXPECT_EQ(own.camera.position(), before.position());
  EXPECT_EQ(own.camera.forward(), before.forward());
  EXPECT_EQ(own.camera.fov(), before.fov());

  Scene framed = frame_obj(dir.write("t.obj", "v 0 0 0\nv 4 0 0\nv 0 1 0\nf 1 2 3\n"));
  ASSERT_TRUE(framed.framed_bounds.has_value());
  const vec4 at_4_3 = framed.camera.position();
  fit_framed_camera(framed, 100, 300);  // portrait: further away, in the same direction
  const vec4 centre = framed.framed_bounds->center();
  EXPECT_GT(float(dot(framed.camera.position() - centre, framed.camera.position() - centre)),
            2.0f * float(dot(at_4_3 - centre, at_4_3 - centre)));
  EXPECT_GT(float(dot(normalize(framed.camera.position() - centre), normalize(at_4_3 - centre))),
            0.9999f);
}

}  // namespace
}  // namespace rt2::io
