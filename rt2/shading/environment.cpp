// rt2/shading/environment.cpp — the environment's factories, its prefiltering and its lookups.
#include "rt2/shading/environment.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>

#include "rt2/shading/brdf.h"
#include "rt2/base/error.h"
#include "rt2/shading/sampling.h"

namespace rt2 {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// The sizes and sample counts documented in environment.h.
constexpr int kMaxSpecularWidth = 512;  // level 0, each side
constexpr int kMinSpecularWidth = 32;   // the roughest levels
constexpr std::uint32_t kSpecularSamples = 128;
constexpr int kSkyWidth = 256;
constexpr int kSkyHeight = 128;

// x clamped to [0, 1], NaN to 0 (a lookup must never index with NaN).

void check_finite_nonnegative(const char* what, float value) {
  if (!(std::isfinite(value) && value >= 0.0f))
    throw Error(std::string("environment: ") + what + " must be finite and >= 0 (got " +
                std::to_string(value) + ")");
}
void check_rotation(float rotation_degrees) {
  if (!std::isfinite(rotation_degrees))
    throw Error("environment: rotation must be finite (got " + std::to_string(rotation_degrees) +
                " degrees)");
}

// Index i of n cells scaled to m cells: i * m / n, in 64 bits (i * m overflows an int for
// sides of 46,341 texels and more).
int scaled(int i, int m, int n) { return int(std::int64_t(i) * m / n); }

// `src` resampled to w x h. When both sides shrink, each output texel is the solid-angle
// weighted mean of the source texels whose centres fall in it (a partition: every source
// texel counts once); otherwise the source is read bilinearly at the output's centres.
// Either way a constant map stays exactly constant up to rounding. Rows so close to a pole
// that their solid angle is 0 in float (maps hundreds of thousands of texels tall) are
// averaged with equal weights.
EquirectMap resample(const EquirectMap& src, int w, int h) {
  EquirectMap dst(w, h);
  const bool shrink = w <= src.width && h <= src.height;
#pragma omp parallel for schedule(dynamic, 1)
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (!shrink) {
        dst.at(x, y) = src.bilinear(dst.texel_direction(x, y));
        continue;
      }
      const int y0 = scaled(y, src.height, h), y1 = scaled(y + 1, src.height, h);
      const int x0 = scaled(x, src.width, w), x1 = scaled(x + 1, src.width, w);
      vec4 sum, plain;
      float weight = 0.0f;
      for (int sy = y0; sy < y1; ++sy) {
        const float row_weight = texel_solid_angle(sy, src.width, src.height);
        vec4 row;
        for (int sx = x0; sx < x1; ++sx) row += src.at(sx, sy);
        sum += row * row_weight;
        plain += row;
        weight += row_weight * float(x1 - x0);
      }
      dst.at(x, y) = weight > 0.0f ? sum * (1.0f / weight)
                                   : plain * (1.0f / (float(y1 - y0) * float(x1 - x0)));
    }
  }
  return dst;
}

// The source and its halvings down to 1 x 1, for filtered importance sampling.
struct MipChain {
  const EquirectMap& source;        // level 0
  std::vector<EquirectMap> halved;  // levels 1, 2, ...

  explicit MipChain(const EquirectMap& s) : source(s) {
    for (const EquirectMap* last = &source; last->width > 1 || last->height > 1;
         last = &halved.back())
      halved.push_back(resample(*last, std::max(1, last->width / 2), std::max(1, last->height / 2)));
  }
  const EquirectMap& level(std::size_t l) const { return l == 0 ? source : halved[l - 1]; }
  // Trilinear: bilinear in the two levels around `lod` (clamped), blended linearly.
  vec4 lookup(const vec4& dir, float lod) const {
    const Uv uv = direction_to_uv(dir);
    const float top = float(halved.size());
    const float l = std::clamp(lod, 0.0f, top);
    const int l0 = int(l);
    if (float(l0) == top) return level(std::size_t(l0)).bilinear(uv);
    const vec4 a = level(std::size_t(l0)).bilinear(uv);
    const vec4 b = level(std::size_t(l0) + 1).bilinear(uv);
    return a + (b - a) * (l - float(l0));
  }
};

// E(n) / pi of the source as 9 spherical-harmonic coefficients: the source's radiance
// projected on bands 0 ... 2 by quadrature over its texels (world directions, the rotation
// applied), each band then convolved with the clamped cosine (A_0 = pi, A_1 = 2 pi / 3,
// A_2 = pi / 4) and divided by pi. A map under 64 x 32 texels is integrated at 64 x 32
// points or more, each texel's value over its whole extent: a map one texel wide holds
// the same radiance at every longitude, which its one column of centres would not show.
// Such a map's long side is first shrunk to 1024 texels (resample), which bounds the
// points of a 1 x 2^28 map.
IrradianceSh project_irradiance(const EquirectMap& map, float u_shift) {
  constexpr int kLongSide = 1024;
  EquirectMap shrunk;
  const bool thin = map.width < 64 || map.height < 32;
  if (thin && (map.width > kLongSide || map.height > kLongSide))
    shrunk = resample(map, std::min(map.width, kLongSide), std::min(map.height, kLongSide));
  const EquirectMap& source = shrunk.texels.empty() ? map : shrunk;
  const int ku = (64 + source.width - 1) / source.width;  // points per texel, 1 from 64 up
  const int kv = (32 + source.height - 1) / source.height;
  const int grid_w = source.width * ku, grid_h = source.height * kv;
  std::array<double, 27> sum{};
  for (int gy = 0; gy < grid_h; ++gy) {
    const int y = gy / kv;
    const float solid_angle = texel_solid_angle(gy, grid_w, grid_h);
    for (int gx = 0; gx < grid_w; ++gx) {
      const int x = gx / ku;
      // the world direction whose lookup (map_uv adds u_shift) is this point
      const vec4 d = uv_to_direction({(float(gx) + 0.5f) / float(grid_w) - u_shift,
                                      (float(gy) + 0.5f) / float(grid_h)});
      const std::array<float, 9> b = sh9(d);
      const vec4& l = source.at(x, y);
      for (int k = 0; k < 9; ++k)
        for (int c = 0; c < 3; ++c) sum[std::size_t(3 * k + c)] += double(l[c] * b[std::size_t(k)] * solid_angle);
    }
  }
  IrradianceSh sh;
  for (int k = 0; k < 9; ++k) {
    const double band = k == 0 ? 1.0 : (k < 4 ? 2.0 / 3.0 : 0.25);
    sh.c[std::size_t(k)] = vec4(float(sum[std::size_t(3 * k)] * band), float(sum[std::size_t(3 * k + 1)] * band),
                                float(sum[std::size_t(3 * k + 2)] * band));
  }
  return sh;
}

// One GGX sample of a specular level, in the local frame of n = v = r (n along +z).
struct LobeSample {
  vec4 l;     // the light direction
  float n_dot_l;
  float lod;  // the source mip level whose texels match the sample's solid angle
};

// The samples of roughness `roughness` over a source of source_texels texels: Hammersley
// points mapped to GGX half vectors, reflected about them. With n = v, the density of l is
// D(h) (n·h) / (4 v·h) = D(h) / 4; a sample stands for the solid angle 1 / (N pdf), and
// reads the mip level where a texel is that large (Colbert and Krivanek 2007, eq. 13,
// with their bias of one level). The average texel of level 0 is 4 pi / texels.
std::vector<LobeSample> lobe_samples(float roughness, float source_texels) {
  const float alpha = roughness * roughness;
  const float texel_solid_angle0 = 4.0f * kPi / source_texels;
  std::vector<LobeSample> samples;
  for (std::uint32_t i = 0; i < kSpecularSamples; ++i) {
    const vec4 h = sample_ggx_half(hammersley(i, kSpecularSamples), alpha);
    const float n_dot_h = h[2];
    const vec4 l = 2.0f * n_dot_h * h - vec4(0.0f, 0.0f, 1.0f);
    if (l[2] <= 0.0f) continue;
    const float pdf = ggx_d(n_dot_h, h[0] * h[0] + h[1] * h[1], alpha) * 0.25f;
    const float sample_solid_angle = 1.0f / (float(kSpecularSamples) * pdf);
    const float lod = 0.5f * std::log2(sample_solid_angle / texel_solid_angle0) + 1.0f;
    samples.push_back({l, l[2], std::max(lod, 0.0f)});
  }
  return samples;
}

// A w x h map of the radiance prefiltered with the GGX lobe of `roughness`, weighted by
// n·l (Karis 2013, "Real Shading in Unreal Engine 4", PrefilterEnvMap).
EquirectMap prefilter_specular(const MipChain& mips, float roughness, int w, int h) {
  const EquirectMap& source = mips.source;
  const std::vector<LobeSample> samples =
      lobe_samples(roughness, float(source.width) * float(source.height));
  float weight = 0.0f;
  for (const LobeSample& s : samples) weight += s.n_dot_l;
  EquirectMap out(w, h);
#pragma omp parallel for schedule(dynamic, 1)
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const Frame frame(out.texel_direction(x, y));
      vec4 sum;
      for (const LobeSample& s : samples)
        sum += mips.lookup(frame.to_world(s.l), s.lod) * s.n_dot_l;
      out.at(x, y) = sum * (1.0f / weight);
    }
  }
  return out;
}

// GLSL's smoothstep: 0 below e0, 1 above e1, a cubic between (e0 > e1 flips it).
float smoothstep(float e0, float e1, float x) {
  const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// The procedural sky's radiance towards unit d (sun: unit, in the map's frame).
vec4 sky_radiance(const vec4& d, const vec4& sun) {
  const vec4 zenith(0.16f, 0.34f, 0.80f);
  const vec4 horizon(0.72f, 0.80f, 0.92f);
  const vec4 ground(0.20f, 0.15f, 0.10f);
  const vec4 sun_color(1.0f, 0.92f, 0.80f);
  const float y = d[1];
  // Above the horizon: the zenith's blue whitens towards the horizon.
  const float t = 1.0f - std::max(y, 0.0f);
  const vec4 air = zenith + (horizon - zenith) * (t * t * t);
  // The sun's disk (2 degrees, with an edge softened over 0.6 degrees so that a 256-texel
  // map does not alias it) and a glow that falls off over ~6 degrees.
  const float angle = std::acos(std::clamp(float(dot(d, sun)), -1.0f, 1.0f));
  constexpr float kDeg = kPi / 180.0f;
  const float disk = 1.0f - smoothstep(1.7f * kDeg, 2.3f * kDeg, angle);
  const float glow = std::exp(-angle / (6.0f * kDeg));
  const vec4 sky = air + sun_color * (150.0f * disk + 3.0f * glow);
  // Below: the ground, blended in over two degrees so that the horizon is no hard edge.
  const float below = smoothstep(0.0f, -0.035f, y);
  return sky + (ground - sky) * below;
}

}  // namespace

Environment Environment::uniform(const vec4& color) {
  Environment env;
  env.source_ = EquirectMap(1, 1);
  env.source_.at(0, 0) = color;
  env.irradiance_.c[0] = color * (1.0f / 0.282095f);  // band 0 alone
  env.specular_.assign(kSpecularLevels, env.source_);
  return env;
}

Environment Environment::from_image(int width, int height, std::vector<float> rgb,
                                    float intensity, float rotation_degrees) {
  if (width <= 0 || height <= 0)
    throw Error("environment image: width and height must be positive (got " +
                std::to_string(width) + " x " + std::to_string(height) + ")");
  const std::size_t count = std::size_t(width) * std::size_t(height);
  if (rgb.size() != 3 * count)
    throw Error("environment image: " + std::to_string(width) + " x " + std::to_string(height) +
                " needs " + std::to_string(3 * count) + " floats, got " +
                std::to_string(rgb.size()));
  check_finite_nonnegative("intensity", intensity);
  check_rotation(rotation_degrees);
  Environment env;
  for (float& c : rgb)
    if (!(std::isfinite(c) && c >= 0.0f)) {
      c = 0.0f;
      ++env.replaced_values_;
    }
  env.source_ = EquirectMap(width, height);
  for (std::size_t i = 0; i < count; ++i)
    env.source_.texels[i] = vec4(rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]) * intensity;
  std::vector<float>().swap(rgb);  // not held while prefiltering
  env.u_shift_ = rotation_degrees / 360.0f;
  env.prefilter();
  return env;
}

double Environment::bytes_for_image(int width, int height) {
  // The argument's 3 floats and the source's vec4 per texel while converting; then the
  // source and its halvings (a third of it) while prefiltering, and the specular levels.
  const double texels = double(width) * double(height);
  const double specular = 2.0 * kMaxSpecularWidth * kMaxSpecularWidth * sizeof(vec4);
  return texels * double(3 * sizeof(float) + sizeof(vec4)) + specular;
}

Environment Environment::sky(const vec4& sun_direction, float intensity, float rotation_degrees) {
  const float length2 = dot(sun_direction, sun_direction);
  if (!(std::isfinite(length2) && length2 > 0.0f))
    throw Error("environment sky: the sun direction must be finite and nonzero");
  check_finite_nonnegative("sky intensity", intensity);
  check_rotation(rotation_degrees);
  const vec4 sun = normalize(vec4(sun_direction[0], sun_direction[1], sun_direction[2]));
  Environment env;
  env.source_ = EquirectMap(kSkyWidth, kSkyHeight);
  // Each texel averages 4 x 4 points, so that the sun's edge and the horizon are
  // antialiased.
  constexpr int kSub = 4;
#pragma omp parallel for schedule(dynamic, 1)
  for (int y = 0; y < kSkyHeight; ++y)
    for (int x = 0; x < kSkyWidth; ++x) {
      vec4 sum;
      for (int sy = 0; sy < kSub; ++sy)
        for (int sx = 0; sx < kSub; ++sx) {
          const Uv uv{(float(x) + (float(sx) + 0.5f) / kSub) / float(kSkyWidth),
                      (float(y) + (float(sy) + 0.5f) / kSub) / float(kSkyHeight)};
          sum += sky_radiance(uv_to_direction(uv), sun);
        }
      env.source_.at(x, y) = sum * (intensity / float(kSub * kSub));
    }
  env.u_shift_ = rotation_degrees / 360.0f;
  env.prefilter();
  return env;
}

void Environment::prefilter() {
  const auto start = std::chrono::steady_clock::now();
  irradiance_ = project_irradiance(source_, u_shift_);
  // Level 0, the mirror: the source itself, at most kMaxSpecularWidth on each side.
  int w = source_.width, h = source_.height;
  if (w > kMaxSpecularWidth) {
    h = std::max(1, scaled(h, kMaxSpecularWidth, w));
    w = kMaxSpecularWidth;
  }
  if (h > kMaxSpecularWidth) {
    w = std::max(1, scaled(w, kMaxSpecularWidth, h));
    h = kMaxSpecularWidth;
  }
  specular_.clear();
  specular_.push_back(resample(source_, w, h));
  const MipChain mips(source_);
  for (int k = 1; k < kSpecularLevels; ++k) {
    w = std::max(kMinSpecularWidth, w / 2);
    h = std::max(kMinSpecularWidth / 2, h / 2);
    const float roughness = float(k) / float(kSpecularLevels - 1);
    specular_.push_back(prefilter_specular(mips, roughness, w, h));
  }
  prefilter_seconds_ =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace rt2
