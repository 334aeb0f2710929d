// rt2/shading/brdf_lut.h — the directional albedo of brdf.h's specular lobe, tabulated: the
// split-sum table of image-based lighting (Karis 2013) and the energy balance of the
// diffuse term (brdf.h). Computed once per process on the first lookup, so renders without
// physically based materials never pay for it.
//
// For a view at n·v = mu and a roughness r, the specular lobe D V F of brdf.h reflects the
// fraction E(mu) = integral of D V F(h·v) (n·l) dl = F0 A(mu, r) + B(mu, r) of light arriving
// uniformly from the hemisphere (Schlick's F = F0 (1 - Fc) + Fc with Fc = (1 - h·v)^5, so A
// integrates D V (1 - Fc) n·l and B integrates D V Fc n·l); its cosine-weighted average over
// views is E_avg = F0 A_avg(r) + B_avg(r), A_avg = 2 integral of A(mu) mu dmu, likewise B_avg.
#pragma once

namespace rt2 {

// The table: 64 x 64 entries over mu (at mu = ((i + 0.5) / 64)^2, densest at grazing views
// where E changes fastest) and roughness (j / 63, 0 and 1 included), bilinear in sqrt(mu)
// and roughness, each from 1024 GGX-distributed Hammersley samples with
// alpha = max(r^2, kMinAlpha), the alpha the lights see; the averages from the table itself
// (so that they are the averages of what lookups return).
struct SplitSum {
  float a = 0.0f, b = 0.0f;  // E = F0 a + b
};

// A and B at n·v = n_dot_v (clamped to [0, 1]) and roughness (clamped), bilinear:
// with x = clamp(sqrt(clamp01(n_dot_v)) kMu - 0.5, 0, kMu - 1), y = clamp01(roughness)
// (kRoughness - 1), i = min(int(x), kMu - 2), j = min(int(y), kRoughness - 2), the blend
// a + (b - a) t across i, i + 1 (t = x - i) of rows j and j + 1, then across the rows
// (t = y - j); clamp01(x) = x > 0 ? (x < 1 ? x : 1) : 0.
SplitSum split_sum(float n_dot_v, float roughness);

// The table itself, for lookups that must return what split_sum returns (the shading
// lanes, rt2/kernel/brdf_lanes.h): entry[j kMu + i] for column i and roughness row j.
struct SplitSumTable {
  static constexpr int kMu = 64;          // columns, over sqrt(mu)
  static constexpr int kRoughness = 64;   // rows, over roughness
  SplitSum entry[kRoughness * kMu];
  SplitSum average[kRoughness];
};
const SplitSumTable& split_sum_table();

// A_avg and B_avg at `roughness` (clamped), linear between the table's rows.
SplitSum split_sum_average(float roughness);

}  // namespace rt2
