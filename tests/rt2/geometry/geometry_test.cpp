// Primitives against hand-computed cases: planes, spheres (with the thesis's bug fixed),
// triangles (formula 10), boxes (slab test) and the camera.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "rt2/geometry/aabb.h"
#include "rt2/scene/camera.h"
#include "rt2/base/error.h"
#include "rt2/geometry/plane.h"
#include "rt2/geometry/sphere.h"
#include "rt2/geometry/triangle.h"

namespace rt2 {
namespace {

Ray ray(vec4 o, vec4 d) { return Ray(o, normalize(d)); }

// --- plane -------------------------------------------------------------------------------
TEST(Plane, HitDistanceIsMinusPNPlusDOverDirN) {
  const Plane ground{vec4(0, 1, 0), 2.0f};  // y = -2
  float t;
  ASSERT_TRUE(intersect(ground, ray(vec4(0, 3, 0), vec4(0, -1, 0)), 0.0f, kInfinity, t));
  EXPECT_FLOAT_EQ(t, 5.0f);
  ASSERT_TRUE(intersect(ground, ray(vec4(0, 3, 0), vec4(1, -1, 0)), 0.0f, kInfinity, t));
  EXPECT_NEAR(t, 5.0f * std::sqrt(2.0f), 1e-5f);
}

TEST(Plane, ParallelRayMisses) {
  const Plane ground{vec4(0, 1, 0), 0.0f};
  float t;
  EXPECT_FALSE(intersect(ground, ray(vec4(0, 1, 0), vec4(1, 0, 0)), 0.0f, kInfinity, t));
  EXPECT_FALSE(intersect(ground, ray(vec4(0, 0, 0), vec4(1, 0, 0)), 0.0f, kInfinity, t));
}

TEST(Plane, HitBehindOriginOrBeyondTMaxIsRejected) {
  const Plane ground{vec4(0, 1, 0), 0.0f};
  float t;
  EXPECT_FALSE(intersect(ground, ray(vec4(0, 1, 0), vec4(0, 1, 0)), 0.0f, kInfinity, t));
  EXPECT_FALSE(intersect(ground, ray(vec4(0, 1, 0), vec4(0, -1, 0)), 0.0f, 0.5f, t));
}

// --- sphere ------------------------------------------------------------------------------
TEST(Sphere, HitsTheNearSideFirst) {
  const Sphere s{vec4(0, 0, -5), 1.0f};
  float t;
  ASSERT_TRUE(intersect(s, ray(vec4(0, 0, 0), vec4(0, 0, -1)), 0.0f, kInfinity, t));
  EXPECT_FLOAT_EQ(t, 4.0f);
}

TEST(Sphere, ConstantTermIsOcSquaredMinusRSquaredNotTheThesisTwice) {
  // With the thesis's c = 2|P-C|^2 - r^2 this ray (|P-C| = 3, r = 2) would give roots of
  // t^2 - 6t + 14 = 0: no real root, a miss. The right c = 9 - 4 = 5 gives t = 1.
  const Sphere s{vec4(3, 0, 0), 2.0f};
  float t;
  ASSERT_TRUE(intersect(s, ray(vec4(0, 0, 0), vec4(1, 0, 0)), 0.0f, kInfinity, t));
  EXPECT_FLOAT_EQ(t, 1.0f);
}

TEST(Sphere, RayPassingBesideMisses) {
  const Sphere s{vec4(0, 0, -5), 1.0f};
  float t;
  EXPECT_FALSE(intersect(s, ray(vec4(0, 1.01f, 0), vec4(0, 0, -1)), 0.0f, kInfinity, t));
}

TEST(Sphere, SphereBehindTheOriginIsNotHit) {
  const Sphere s{vec4(0, 0, 5), 1.0f};
  float t;
  EXPECT_FALSE(intersect(s, ray(vec4(0, 0, 0), vec4(0, 0, -1)), 0.0f, kInfinity, t));
}

TEST(Sphere, OriginInsideHitsTheFarSide) {
  const Sphere s{vec4(0, 0, 0), 2.0f};
  float t;
  ASSERT_TRUE(intersect(s, ray(vec4(0.5f, 0, 0), vec4(1, 0, 0)), 0.0f, kInfinity, t));
  EXPECT_FLOAT_EQ(t, 1.5f);
}

TEST(Sphere, TangentRayTouchesAtOnePoint) {
  const Sphere s{vec4(0, 1, -5), 1.0f};
  float t;
  ASSERT_TRUE(intersect(s, ray(vec4(0, 0, 0), vec4(0, 0, -1)), 0.0f, kInfinity, t));
  EXPECT_NEAR(t, 5.0f, 1e-3f);
}

TEST(Sphere, TinySphereFarAwayIsHitAccurately) {
  // r = 1e-4 at distance 1e4: b^2 - c would cancel to nothing in float; the stable form
  // finds the hit to about an ulp of the distance.
  const Sphere s{vec4(0, 0, -1e4f), 1e-4f};
  float t;
  ASSERT_TRUE(intersect(s, ray(vec4(0, 0, 0), vec4(0, 0, -1)), 0.0f, kInfinity, t));
  EXPECT_NEAR(t, 1e4f - 1e-4f, 2e-3f);
  ASSERT_TRUE(intersect(s, ray(vec4(0, 0.5e-4f, 0), vec4(0, 0, -1)), 0.0f, kInfinity, t));
}

// --- triangle ----------------------------------------------------------------------------
const Triangle kTri = Triangle::make(vec4(0, 0, 0), vec4(1, 0, 0), vec4(0, 1, 0));

TEST(Triangle, FormulaTenGivesHandComputedTUV) {
  float t, u, v;
  ASSERT_TRUE(intersect(kTri, ray(vec4(0.2f, 0.3f, 1), vec4(0, 0, -1)), 0.0f, kInfinity, t, u, v));
  EXPECT_FLOAT_EQ(t, 1.0f);
  EXPECT_FLOAT_EQ(u, 0.2f);  // weight of V1
  EXPECT_FLOAT_EQ(v, 0.3f);  // weight of V2
}

TEST(Triangle, BarycentricsReproduceTheHitPoint) {
  const Triangle tri = Triangle::make(vec4(1, 2, 3), vec4(4, -1, 2), vec4(-2, 0, 5));
  const vec4 target = 0.5f * tri.vertex(0) + 0.3f * tri.vertex(1) + 0.2f * tri.vertex(2);
  const vec4 org(7, 8, 9);
  float t, u, v;
  const Ray r = ray(org, target - org);
  ASSERT_TRUE(intersect(tri, r, 0.0f, kInfinity, t, u, v));
  const vec4 p = tri.point(u, v);
  EXPECT_NEAR(calc_distance(p, target), 0.0f, 1e-5f);
  EXPECT_NEAR(calc_distance(r.at(t), target), 0.0f, 1e-5f);
  EXPECT_NEAR(u, 0.3f, 1e-6f);
  EXPECT_NEAR(v, 0.2f, 1e-6f);
}

TEST(Triangle, RaysOutsideEachEdgeMiss) {
  float t, u, v;
  EXPECT_FALSE(intersect(kTri, ray(vec4(-0.1f, 0.3f, 1), vec4(0, 0, -1)), 0, kInfinity, t, u, v));
  EXPECT_FALSE(intersect(kTri, ray(vec4(0.3f, -0.1f, 1), vec4(0, 0, -1)), 0, kInfinity, t, u, v));
  EXPECT_FALSE(intersect(kTri, ray(vec4(0.6f, 0.6f, 1), vec4(0, 0, -1)), 0, kInfinity, t, u, v));
}

TEST(Triangle, ParallelRayMisses) {
  float t, u, v;
  EXPECT_FALSE(intersect(kTri, ray(vec4(-1, 0.2f, 0), vec4(1, 0, 0)), 0, kInfinity, t, u, v));
  EXPECT_FALSE(intersect(kTri, ray(vec4(-1, 0.2f, 0.5f), vec4(1, 0, 0)), 0, kInfinity, t, u, v));
}

TEST(Triangle, HitBehindOriginIsRejected) {
  float t, u, v;
  EXPECT_FALSE(intersect(kTri, ray(vec4(0.2f, 0.2f, 1), vec4(0, 0, 1)), 0, kInfinity, t, u, v));
}

TEST(Triangle, BackFacesAreHitToo) {
  float t, u, v;
  ASSERT_TRUE(intersect(kTri, ray(vec4(0.2f, 0.2f, -1), vec4(0, 0, 1)), 0, kInfinity, t, u, v));
  EXPECT_FLOAT_EQ(t, 1.0f);
}

TEST(Triangle, DegenerateTriangleNeverHits) {
  const Triangle line = Triangle::make(vec4(0, 0, 0), vec4(1, 0, 0), vec4(2, 0, 0));
  const Triangle point = Triangle::make(vec4(0, 0, 0), vec4(0, 0, 0), vec4(0, 0, 0));
  float t, u, v;
  for (const vec4& d : {vec4(0, 0, -1), vec4(0, -1, 0), vec4(1, -1, -1)}) {
    EXPECT_FALSE(intersect(line, ray(vec4(0.5f, 0.5f, 0.5f), d), 0, kInfinity, t, u, v));
    EXPECT_FALSE(intersect(point, ray(vec4(0.5f, 0.5f, 0.5f), d), 0, kInfinity, t, u, v));
  }
}

TEST(Triangle, NormalIsCounterClockwiseCross) {
  EXPECT_EQ(normalize(kTri.n), vec4(0, 0, 1));  // (V1-V0) x (V2-V0) for CCW seen from +z
  EXPECT_EQ(kTri.vertex(1), vec4(1, 0, 0));
  EXPECT_EQ(kTri.vertex(2), vec4(0, 1, 0));
}

// WatertightRay reads its axes from a table (kWatertightAxes) instead of branching. Oracle:
// the branching rule of Woop et al. written out as branches, on every direction whose
// components are drawn from values with ties, zeros of both signs, infinities and NaN.
TEST(Triangle, WatertightRayTakesTheSameAxesAsTheBranchingRuleOnTiesZerosAndNan) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const float values[] = {0.0f, -0.0f, 1.0f, -1.0f, 2.0f, -2.0f, 0.5f, -3.0f, inf, -inf, nan};
  int checked = 0;
  for (float x : values)
    for (float y : values)
      for (float z : values) {
        const Ray r(vec4(0.0f, 0.0f, 0.0f), vec4(x, y, z));
        const float ax = std::fabs(x), ay = std::fabs(y), az = std::fabs(z);
        const int kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
        int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
        if (r.dir[kz] < 0.0f) std::swap(kx, ky);
        const WatertightRay w(r);
        EXPECT_EQ(w.kz, kz) << x << " " << y << " " << z;
        EXPECT_EQ(w.kx, kx) << x << " " << y << " " << z;
        EXPECT_EQ(w.ky, ky) << x << " " << y << " " << z;
        ++checked;
      }
  EXPECT_EQ(checked, 11 * 11 * 11);
}

// --- boxes -------------------------------------------------------------------------------
const Aabb kBox{vec4(-1, -1, -1), vec4(1, 1, 1)};

TEST(Aabb, SlabTestReturnsTheEntryDistance) {
  const RayPre r(ray(vec4(0, 0, 5), vec4(0, 0, -1)));
  EXPECT_NEAR(slab_entry(kBox.lo, kBox.hi, r, 0.0f, kInfinity), 4.0f, 1e-6f);
  const RayPre inside(ray(vec4(0, 0, 0), vec4(0, 0, -1)));
  EXPECT_EQ(slab_entry(kBox.lo, kBox.hi, inside, 0.0f, kInfinity), 0.0f);
}

TEST(Aabb, RaysBesideBehindOrBeyondTMaxMiss) {
  EXPECT_EQ(slab_entry(kBox.lo, kBox.hi, RayPre(ray(vec4(2, 0, 5), vec4(0, 0, -1))), 0, kInfinity),
            kInfinity);
  EXPECT_EQ(slab_entry(kBox.lo, kBox.hi, RayPre(ray(vec4(0, 0, 5), vec4(0, 0, 1))), 0, kInfinity),
            kInfinity);
  EXPECT_EQ(slab_entry(kBox.lo, kBox.hi, RayPre(ray(vec4(0, 0, 5), vec4(0, 0, -1))), 0, 3.9f),
            kInfinity);
}

TEST(Aabb, ZeroDirectionComponentsUseInfiniteReciprocals) {
  // dir = (0, 0, -1): x and y reciprocals are inf; inside the x/y slabs -> hit, outside -> miss
  EXPECT_NEAR(slab_entry(kBox.lo, kBox.hi, RayPre(ray(vec4(0.5f, -0.5f, 3), vec4(0, 0, -1))), 0, kInfinity),
              2.0f, 1e-6f);
  EXPECT_EQ(slab_entry(kBox.lo, kBox.hi, RayPre(ray(vec4(1.5f, 0, 3), vec4(0, 0, -1))), 0, kInfinity),
            kInfinity);
}

TEST(Aabb, RayLyingInAFacePlaneCountsAsInside) {
  // Origin exactly on x = 1 (the box's face) with zero x direction: 0 * inf = NaN must not
  // cull the box.
  EXPECT_NEAR(slab_entry(kBox.lo, kBox.hi, RayPre(ray(vec4(1, 0, 3), vec4(0, 0, -1))), 0, kInfinity),
              2.0f, 1e-6f);
  EXPECT_NEAR(slab_entry(kBox.lo, kBox.hi, RayPre(ray(vec4(-1, 1, 3), vec4(0, 0, -1))), 0, kInfinity),
              2.0f, 1e-6f);
}

TEST(Aabb, GrowAreaAndAxisBookkeeping) {
  Aabb b;
  EXPECT_TRUE(b.is_empty());
  EXPECT_EQ(b.area(), 0.0f);
  b.grow(vec4(0, 0, 0));
  b.grow(vec4(4, 2, 1));
  EXPECT_FALSE(b.is_empty());
  EXPECT_FLOAT_EQ(b.area(), 2 * (8 + 2 + 4));
  EXPECT_EQ(b.longest_axis(), 0);
  EXPECT_EQ(b.center(), vec4(2, 1, 0.5f));
}

// --- camera ------------------------------------------------------------------------------
TEST(Camera, CentreRayIsTheViewDirection) {
  const Camera cam = Camera::look_at(vec4(1, 2, 3), vec4(1, 2, -7), vec4(0, 1, 0), 60.0f);
  const Ray r = cam.ray(50.0f, 50.0f, 100, 100);
  EXPECT_EQ(r.org, vec4(1, 2, 3));
  EXPECT_NEAR(r.dir[2], -1.0f, 1e-6f);
  EXPECT_NEAR(r.dir[0], 0.0f, 1e-6f);
  EXPECT_NEAR(r.dir[1], 0.0f, 1e-6f);
}

TEST(Camera, CornerRaysSpanTheFieldOfView) {
  const float fov = 90.0f;
  const Camera cam = Camera::look_at(vec4(0, 0, 0), vec4(0, 0, -1), vec4(0, 1, 0), fov);
  // Top-left corner of a 200x100 image: x = -aspect tan(45) = -2, y = +1.
  const Ray tl = cam.ray(0.0f, 0.0f, 200, 100);
  const vec4 expect_tl = normalize(vec4(-2, 1, -1));
  EXPECT_NEAR(calc_distance(tl.dir, expect_tl), 0.0f, 1e-6f);
  const Ray br = cam.ray(200.0f, 100.0f, 200, 100);
  EXPECT_NEAR(calc_distance(br.dir, normalize(vec4(2, -1, -1))), 0.0f, 1e-6f);
  // The vertical angle between the top-middle and bottom-middle rays is the fov.
  const float a = std::acos(float(dot(cam.ray(100, 0, 200, 100).dir, cam.ray(100, 100, 200, 100).dir)));
  EXPECT_NEAR(a * 180.0f / std::numbers::pi_v<float>, fov, 1e-3f);
}

TEST(Camera, RayDirectionsAreUnitLength) {
  const Camera cam = Camera::look_at(vec4(3, 1, 2), vec4(0, 0, 0), vec4(0, 1, 0), 45.0f);
  for (float x : {0.0f, 13.5f, 639.9f})
    for (float y : {0.0f, 240.0f, 479.9f}) EXPECT_NEAR(float(dot(cam.ray(x, y, 640, 480).dir, cam.ray(x, y, 640, 480).dir)), 1.0f, 1e-6f);
}

TEST(Camera, BasisIsOrthonormalAndRightHanded) {
  const Camera cam(vec4(0, 0, 0), vec4(1, 1, -1), vec4(0, 1, 0), 50.0f);
  EXPECT_NEAR(float(dot(cam.forward(), cam.up())), 0.0f, 1e-6f);
  EXPECT_NEAR(float(dot(cam.forward(), cam.right())), 0.0f, 1e-6f);
  EXPECT_NEAR(float(dot(cam.up(), cam.right())), 0.0f, 1e-6f);
  EXPECT_NEAR(calc_distance(cross(cam.right(), cam.up()), -cam.forward()), 0.0f, 1e-6f);
  EXPECT_GT(cam.up()[1], 0.0f);
}

TEST(Camera, RejectsUpParallelToViewAndAbsurdFov) {
  EXPECT_THROW(Camera(vec4(0, 0, 0), vec4(0, 1, 0), vec4(0, 1, 0), 60), Error);
  EXPECT_THROW(Camera(vec4(0, 0, 0), vec4(0, 0, -1), vec4(0, 1, 0), 0), Error);
  EXPECT_THROW(Camera(vec4(0, 0, 0), vec4(0, 0, -1), vec4(0, 1, 0), 180), Error);
  EXPECT_THROW(Camera::look_at(vec4(1, 1, 1), vec4(1, 1, 1), vec4(0, 1, 0), 60), Error);
}

}  // namespace
}  // namespace rt2
