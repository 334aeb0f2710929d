// tests/rt2/bvh/quantized_node_test.cpp — the quantized wide node (QuantizedNode,
// bvh/wide_bvh.h) against its oracle, the boxes it was given: every decoded box holds its
// box, each plane is the nearest one on the outer side, the decode is exact (an 8-bit
// integer times a normal power of two) so every kernel decodes the same float, at every
// magnitude a float takes; and trees of quantized nodes answer rays as the plain trees do.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "rt2/bvh/accel.h"
#include "rt2/render/trace.h"
#include "tests/rt2/test_util.h"

namespace rt2 {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// Checks node's slots [0, n) against boxes: every decoded plane holds its box's and is 0, a
// normal float or infinite (never a denormal, which flushing would move); no plane could move
// one step inward and still hold it; the step is the least that spans the axis, and an axis
// is unbounded only when no step of 2^120 or less spans it.
template <int N>
void expect_tight_outward(const QuantizedNode<N>& node, const Aabb* boxes, int n) {
  ASSERT_EQ(node.slots(), n);
  ASSERT_EQ(node.used, (1u << n) - 1);
  for (int a = 0; a < 3; ++a) {
    const float s = node.scale(a);
    ASSERT_TRUE(std::isnormal(s)) << "axis " << a;
    ASSERT_LE(s, 0x1p120f);
    const bool unbounded = node.origin[2 * a] == -kInf;
    EXPECT_EQ(unbounded, node.origin[2 * a + 1] == kInf);
    float lo = kInf, hi = -kInf;
    for (int i = 0; i < n; ++i) {
      lo = std::min(lo, boxes[i].lo[a]);
      hi = std::max(hi, boxes[i].hi[a]);
    }
    if (unbounded) {
      EXPECT_FALSE(std::isfinite(lo) && std::isfinite(hi) && lo + 255.0f * 0x1p120f >= hi)
          << "axis " << a << " could have been spanned";
    } else {
      const float o = node.origin[2 * a];
      EXPECT_LE(o, lo);
      EXPECT_GE(o + 255.0f * s, hi);
      if (s > 0x1p-126f) {
        EXPECT_LT(o + 255.0f * (s / 2), hi) << "a finer step spans the axis";
      }
    }
    for (int i = 0; i < n; ++i) {
      const Aabb d = node.box(i);
      for (int row = 2 * a; row <= 2 * a + 1; ++row) {
        const float p = node.plane(row, i);
        EXPECT_TRUE(p == 0.0f || std::isnormal(p) || std::isinf(p)) << "plane " << p;
      }
      EXPECT_LE(d.lo[a], boxes[i].lo[a]) << "slot " << i << " axis " << a;
      EXPECT_GE(d.hi[a], boxes[i].hi[a]) << "slot " << i << " axis " << a;
      if (unbounded) continue;
      const float o = node.origin[2 * a];
      const int ql = node.q[2 * a][i], qh = node.q[2 * a + 1][i];
      if (ql < 255) {
        EXPECT_GT(o + float(ql + 1) * s, boxes[i].lo[a]) << "lo not tight";
      }
      if (qh > 0) {
        EXPECT_LT(o + float(qh - 1) * s, boxes[i].hi[a]) << "hi not tight";
      }
    }
  }
}

// Random boxes of every size at every position a float holds (denormals included), some
// axes spanning more than 255 * 2^120 or reaching infinity (unbounded then), some flat.
TEST(QuantizedNode, DecodedBoxesHoldTheirBoxesAndAreTightAtEveryMagnitude) {
  std::mt19937 rng(51);
  std::uniform_int_distribution<int> exponent(-149, 127), count(1, 16), kind(0, 6);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), pos(0.0f, 1.0f);
  for (int round = 0; round < 20000; ++round) {
    const int n = count(rng);
    Aabb boxes[16];
    // The node's scale of positions and of sizes, per axis.
    float centre[3], spread[3], size[3];
    for (int a = 0; a < 3; ++a) {
      centre[a] = std::ldexp(u(rng), exponent(rng));
      spread[a] = std::ldexp(pos(rng), exponent(rng));
      size[a] = std::ldexp(pos(rng), exponent(rng));
    }
    for (int i = 0; i < n; ++i)
      for (int a = 0; a < 3; ++a) {
        float lo = centre[a] + spread[a] * u(rng), hi = lo + size[a] * pos(rng);
        switch (kind(rng)) {
          case 0: hi = lo; break;                          // flat
          case 1: lo = -3.4e38f, hi = 3.4e38f; break;      // the whole float range
          case 2: lo = std::max(lo, -3.4e38f); break;
          case 3: hi = kInf; break;                        // a padded box that overflowed
          default: break;
        }
        if (std::isnan(lo) || std::isnan(hi) || std::isinf(lo) || !(hi >= lo)) lo = hi = 0.0f;
        boxes[i].lo[a] = lo;
        boxes[i].hi[a] = hi;
      }
    QuantizedNode<16> node16;
    quantize_boxes(node16, boxes, n);
    expect_tight_outward(node16, boxes, n);
    if (n <= 8) {
      QuantizedNode<8> node8;
      quantize_boxes(node8, boxes, n);
      expect_tight_outward(node8, boxes, n);
    }
    if (n <= 4) {
      QuantizedNode<4> node4;
      quantize_boxes(node4, boxes, n);
      expect_tight_outward(node4, boxes, n);
    }
    if (HasFatalFailure() || HasFailure()) {
      ADD_FAILURE() << "round " << round;
      return;
    }
  }
}

// A scene built with both layouts: every closest hit and every occlusion answer is the same,
// bit for bit, on every ISA, near the origin and far from it, tiny and huge.
TEST(QuantizedNode, QuantizedTreesAnswerEveryRayAsPlainTreesOnEveryIsa) {
  struct Case {
    vec4 offset;
    float scale;
  };
  for (const Case& k : {Case{vec4(0.0f), 1e-3f}, Case{vec4(0.0f), 1.0f}, Case{vec4(0.0f), 1e5f},
                        Case{vec4(3e6f, -2e6f, 1e6f), 100.0f},
                        Case{vec4(1e13f, -1e13f, 5e12f), 1e9f}}) {
      const vec4 offset = k.offset;
      const float scale = k.scale;
      Mesh soup = test::random_soup(2000, 0.3f, 61);
      for (vec4& p : soup.positions) p = offset + scale * p;
      soup.drop_degenerate();
      ASSERT_GT(soup.faces.size(), 1000u);
      const Scene scene = test::geometry_scene({soup});
      for (Isa isa : test::runnable_isas()) {
        BvhConfig plain_config, quantized_config;
        plain_config.nodes = NodeLayout::plain;
        quantized_config.nodes = NodeLayout::quantized;
        const Accel plain = Accel::build(scene, plain_config, isa);
        const Accel quantized = Accel::build(scene, quantized_config, isa);
        ASSERT_FALSE(plain.quantized_nodes());
        ASSERT_TRUE(quantized.quantized_nodes());
        EXPECT_LT(accel_bytes(quantized), accel_bytes(plain));
        const std::vector<Ray> rays = test::random_rays(plain, 4000, 62, 1.5f);
        std::vector<float> t_max(rays.size(), kInfinity);
        for (std::size_t i = 0; i < rays.size(); i += 2) t_max[i] = scale * float(i % 7);
        for (bool watertight : {false, true}) {
          const TraceOptions opt{watertight};
          std::vector<Hit> a(rays.size()), b(rays.size());
          std::vector<std::uint8_t> oa(rays.size()), ob(rays.size());
          trace_closest(plain, opt, rays.data(), t_max.data(), rays.size(), a.data());
          trace_closest(quantized, opt, rays.data(), t_max.data(), rays.size(), b.data());
          trace_occluded(plain, opt, rays.data(), t_max.data(), rays.size(), oa.data());
          trace_occluded(quantized, opt, rays.data(), t_max.data(), rays.size(), ob.data());
          std::size_t differ = 0, hits = 0;
          for (std::size_t i = 0; i < rays.size(); ++i) {
            differ += !test::bitwise_same(a[i], b[i]) || oa[i] != ob[i];
            hits += a[i].found();
          }
          EXPECT_EQ(differ, 0u) << isa_name(isa) << " scale " << scale << " offset "
                                << offset[0] << (watertight ? " watertight" : " fast");
          EXPECT_GT(hits, rays.size() / 10);
        }
      }
    }
}

}  // namespace
}  // namespace rt2
