// rt2/scene/builtin_scene.h: the thesis's test scene built in code. Each test names the property
// it checks: it validates, holds one sphere, one plane, one light and a chair of the
// thesis's size, both objects are perfect mirrors, it needs exactly the expected render
// features, and the camera frames it.
#include "rt2/scene/builtin_scene.h"
#include "rt2/base/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "rt2/geometry/aabb.h"
#include "rt2/geometry/ray.h"

namespace rt2 {
namespace {

const Scene& scene() {
  static const Scene s = make_default_scene();
  return s;
}

// Where p lands in normalised image coordinates (-1 .. 1 across the frame in x and y) for
// an image of the given aspect ratio, by inverting Camera::ray's mapping.
std::pair<float, float> project(const Camera& c, const vec4& p, float aspect) {
  const vec4 d = p - c.position();
  const float depth = dot(d, c.forward());
  const float tan_half = std::tan(0.5f * c.fov() * std::acos(-1.0f) / 180.0f);
  return {float(dot(d, c.right())) / depth / (aspect * tan_half),
          float(dot(d, c.up())) / depth / tan_half};
}

TEST(BuiltinScene, Validates) { EXPECT_NO_THROW(scene().validate()); }

// A scene built in code may leave the per-primitive material arrays short: validate must
// say so rather than read past them.
TEST(BuiltinScene, ValidateRefusesMaterialArraysShorterThanTheirPrimitives) {
  Scene s = scene();
  s.sphere_materials.clear();
  EXPECT_THROW(s.validate(), Error);
  s = scene();
  s.plane_materials.clear();
  EXPECT_THROW(s.validate(), Error);
  s = scene();
  s.material_names.pop_back();
  EXPECT_THROW(s.validate(), Error);
}

TEST(BuiltinScene, HasOneSphereOnePlaneAndOneLight) {
  const Scene& s = scene();
  EXPECT_EQ(s.spheres.size(), 1u);
  EXPECT_EQ(s.sphere_materials.size(), 1u);
  EXPECT_EQ(s.planes.size(), 1u);
  EXPECT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].intensity, 1.0f);
}

TEST(BuiltinScene, MeshesHoldBetween10000And11000Triangles) {
  EXPECT_GE(scene().triangle_count(), 10000u);
  EXPECT_LE(scene().triangle_count(), 11000u);
}

TEST(BuiltinScene, ChairAndSphereArePerfectMirrors) {
  const Scene& s = scene();
  auto is_mirror = [&](std::uint32_t i) {
    const Material& m = s.materials[i];
    return s.material_names[i] == "mirror" && m.reflectivity == 1.0f && !(m.diffuse[0] > 0) &&
           !(m.ambient[0] > 0) && m.has_specular();
  };
  EXPECT_TRUE(is_mirror(s.sphere_materials[0]));
  for (const Mesh& m : s.meshes)
    for (std::uint32_t i : m.face_materials) ASSERT_TRUE(is_mirror(i));
}

TEST(BuiltinScene, GroundIsAMatteCheckerAtYZero) {
  const Scene& s = scene();
  EXPECT_EQ(s.planes[0].n[1], 1.0f);
  EXPECT_EQ(s.planes[0].d, 0.0f);
  const Material& floor = s.materials[s.plane_materials[0]];
  EXPECT_EQ(floor.checker_scale, 0.25f);
  EXPECT_EQ(floor.reflectivity, 0.0f);
}

TEST(BuiltinScene, FeaturesAreReflectionSpecularSpheresPlanesAndTriangles) {
  EXPECT_EQ(scene().features(),
            unsigned(kReflection | kSpecular | kSpheres | kPlanes | kTriangles));
}

TEST(BuiltinScene, SphereRestsOnTheGroundBesideTheChair) {
  const Scene& s = scene();
  const Sphere& ball = s.spheres[0];
  EXPECT_NEAR(ball.center[1] - ball.radius, 0.0f, 1e-6f);
  const Aabb chair = s.meshes[0].bounds();
  EXPECT_GT(ball.center[0] - ball.radius, chair.hi[0]);  // no overlap: to the chair's right
}

TEST(BuiltinScene, CentreRayOfTheCameraHitsTheSceneBounds) {
  const Scene& s = scene();
  const Aabb b = s.bounds();
  for (auto [w, h] : {std::pair{640, 480}, {512, 512}, {1920, 1080}}) {
    const Ray r = s.camera.ray(float(w) / 2, float(h) / 2, w, h);
    EXPECT_LT(slab_entry(b.lo, b.hi, RayPre(r), 0.0f, kInfinity), kInfinity) << w << "x" << h;
  }
}

TEST(BuiltinScene, ChairAndSphereAreInViewAndFillMostOfTheFrame) {
  const Scene& s = scene();
  const Aabb chair = s.meshes[0].bounds();
  const Sphere& ball = s.spheres[0];
  for (float aspect : {4.0f / 3.0f, 1.0f}) {
    float x_lo = 1, x_hi = -1, y_lo = 1, y_hi = -1;
    auto see = [&](const vec4& p) {
      const auto [x, y] = project(s.camera, p, aspect);
      x_lo = std::min(x_lo, x), x_hi = std::max(x_hi, x);
      y_lo = std::min(y_lo, y), y_hi = std::max(y_hi, y);
    };
    for (int c = 0; c < 8; ++c)  // the chair's bounding box corners
      see(vec4(c & 1 ? chair.hi[0] : chair.lo[0], c & 2 ? chair.hi[1] : chair.lo[1],
               c & 4 ? chair.hi[2] : chair.lo[2]));
    for (int k = 0; k < 3; ++k)  // the sphere's extreme points along each axis
      for (float sign : {-1.0f, 1.0f}) {
        vec4 p = ball.center;
        p[static_cast<std::size_t>(k)] += sign * ball.radius;
        see(p);
      }
    EXPECT_GT(x_lo, -1.0f) << "aspect " << aspect;
    EXPECT_LT(x_hi, 1.0f) << "aspect " << aspect;
    EXPECT_GT(y_lo, -1.0f) << "aspect " << aspect;
    EXPECT_LT(y_hi, 1.0f) << "aspect " << aspect;
    EXPECT_GT(x_hi - x_lo, 1.2f) << "aspect " << aspect;  // more than 60% of the width
    EXPECT_GT(y_hi - y_lo, 1.0f) << "aspect " << aspect;  // at least half of the height
  }
}

}  // namespace
}  // namespace rt2
