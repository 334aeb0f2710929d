// rt2/shading/brdf_lut.cpp — the split-sum table (see brdf_lut.h).
#include "rt2/shading/brdf_lut.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "rt2/shading/brdf.h"
#include "rt2/shading/sampling.h"

namespace rt2 {

namespace {

constexpr int kMu = SplitSumTable::kMu;
constexpr int kSize = SplitSumTable::kRoughness;
constexpr std::uint32_t kSamples = 1024;

using Table = SplitSumTable;

// Column i holds mu = x^2 at x = (i + 0.5) / kMu: the albedo changes fastest at grazing
// views (small mu), where the columns are densest.
float column_mu(int i) {
  const float x = (float(i) + 0.5f) / float(kMu);
  return x * x;
}

float clamp01(float x) { return x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f; }

// A and B at one (mu, roughness) by GGX importance sampling: the estimator of
// D V F n·l / pdf with pdf = D (n·h) / (4 v·h) is 4 V (n·l) (v·h) / (n·h) F.
SplitSum integrate(float n_dot_v, float roughness) {
  const float alpha = std::max(roughness * roughness, kMinAlpha);
  const vec4 v(std::sqrt(1.0f - n_dot_v * n_dot_v), 0.0f, n_dot_v);
  double a = 0.0, b = 0.0;
  for (std::uint32_t k = 0; k < kSamples; ++k) {
    const vec4 h = sample_ggx_half(hammersley(k, kSamples), alpha);
    const float v_dot_h = dot(v, h);
    const vec4 l = 2.0f * v_dot_h * h - v;
    const float n_dot_l = l[2];
    if (n_dot_l <= 0.0f || v_dot_h <= 0.0f) continue;
    const float g = 4.0f * smith_visibility(n_dot_v, n_dot_l, alpha) * n_dot_l * v_dot_h / h[2];
    const float fc = schlick_weight(v_dot_h);
    a += double((1.0f - fc) * g);
    b += double(fc * g);
  }
  return {float(a / kSamples), float(b / kSamples)};
}

SplitSum lookup(const Table& t, float n_dot_v, float roughness) {
  const float x = std::clamp(std::sqrt(clamp01(n_dot_v)) * float(kMu) - 0.5f, 0.0f,
                             float(kMu - 1));
  const float y = clamp01(roughness) * float(kSize - 1);
  const int x0 = std::min(int(x), kMu - 2), y0 = std::min(int(y), kSize - 2);
  const float tx = x - float(x0), ty = y - float(y0);
  const auto at = [&](int i, int j) { return t.entry[std::size_t(j * kMu + i)]; };
  const auto mix = [](SplitSum p, SplitSum q, float f) {
    return SplitSum{p.a + (q.a - p.a) * f, p.b + (q.b - p.b) * f};
  };
  return mix(mix(at(x0, y0), at(x0 + 1, y0), tx), mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), tx), ty);
}

Table make_table() {
  Table t;
#pragma omp parallel for schedule(dynamic, 1)
  for (int j = 0; j < kSize; ++j)
    for (int i = 0; i < kMu; ++i)
      t.entry[std::size_t(j * kMu + i)] = integrate(column_mu(i), float(j) / float(kSize - 1));
  // 2 integral of E(mu) mu dmu by the midpoint rule over what lookups return
  constexpr int kSteps = 256;
  for (int j = 0; j < kSize; ++j) {
    double a = 0.0, b = 0.0;
    for (int s = 0; s < kSteps; ++s) {
      const float mu = (float(s) + 0.5f) / float(kSteps);
      const SplitSum e = lookup(t, mu, float(j) / float(kSize - 1));
      a += double(e.a) * mu;
      b += double(e.b) * mu;
    }
    t.average[std::size_t(j)] = {float(2.0 * a / kSteps), float(2.0 * b / kSteps)};
  }
  return t;
}

}  // namespace

const SplitSumTable& split_sum_table() {
  static const Table t = make_table();
  return t;
}

SplitSum split_sum(float n_dot_v, float roughness) { return lookup(split_sum_table(), n_dot_v, roughness); }

SplitSum split_sum_average(float roughness) {
  const Table& t = split_sum_table();
  const float y = clamp01(roughness) * float(kSize - 1);
  const int j = std::min(int(y), kSize - 2);
  const float f = y - float(j);
  const SplitSum p = t.average[std::size_t(j)], q = t.average[std::size_t(j) + 1];
  return {p.a + (q.a - p.a) * f, p.b + (q.b - p.b) * f};
}

}  // namespace rt2
