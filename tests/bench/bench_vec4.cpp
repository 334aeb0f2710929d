// tests/bench/bench_vec4.cpp — the thesis's table 2: formula (11)
//   R = dot(b - (3/4) a, b dot(a, b - a)) b + (1/400) a b dot(a, b)
// evaluated four ways — vec4 expression templates, hand-written SSE intrinsics, a plain
// scalar struct and std::valarray<float> — timed with mlib::Timer in its four modes for
// 10^1 ... 10^7 iterations.
//
// Output: CSV `impl,mode,iterations,cycles` on stdout (plus an informational fifth impl,
// intrinsics_shufdot, see below), then two summary lines
//   et_vs_intrinsics=<median over (mode, iterations) of cycles(et) / cycles(intrinsics)>
//   valarray_vs_et=<median of cycles(valarray) / cycles(et)>
#include <CLI/CLI.hpp>
#include <smmintrin.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <valarray>
#include <vector>

#include "mlib/timer.h"
#include "tests/bench/bench_util.h"
#include "mlib/vec4_functions.h"

namespace {

constexpr std::size_t kPool = 1024;

// --- the four implementations of formula (11) ----------------------------------------
struct EtImpl {
  using V = mlib::vec4;
  static constexpr const char* name = "et";
  static MLIB_INLINE V eval(const V& a, const V& b) {
    return dot(b - 0.75f * a, b * dot(a, b - a)) * b + (1.0f / 400.0f) * a * b * dot(a, b);
  }
};

struct M128 {  // __m128 in a struct: std::vector<__m128> drops its alignment attribute
  __m128 m;
};

struct IntrinsicsImpl {
  using V = M128;
  static constexpr const char* name = "intrinsics";
  static MLIB_INLINE V eval(const V& va, const V& vb) {
    const __m128 a = va.m, b = vb.m;
    const __m128 bma = _mm_sub_ps(b, a);
    const __m128 d_ab_a = _mm_dp_ps(a, bma, 0xFF);
    const __m128 lhs = _mm_sub_ps(b, _mm_mul_ps(_mm_set1_ps(0.75f), a));
    const __m128 d_left = _mm_dp_ps(lhs, _mm_mul_ps(b, d_ab_a), 0xFF);
    const __m128 d_ab = _mm_dp_ps(a, b, 0xFF);
    const __m128 right =
        _mm_mul_ps(_mm_mul_ps(_mm_mul_ps(_mm_set1_ps(1.0f / 400.0f), a), b), d_ab);
    return {_mm_add_ps(_mm_mul_ps(d_left, b), right)};
  }
};

// Informational, not in the thesis: the same intrinsics with the dot product done by
// mulps + two shuffles + two addps instead of dpps. Shows how much of the ET figure is the
// dpps instruction itself on the machine at hand (rt2's dot uses dpps, as specified).
struct IntrinsicsShuffleDotImpl {
  using V = M128;
  static constexpr const char* name = "intrinsics_shufdot";
  static MLIB_INLINE __m128 dp(__m128 a, __m128 b) {
    const __m128 m = _mm_mul_ps(a, b);
    const __m128 s = _mm_add_ps(m, _mm_shuffle_ps(m, m, _MM_SHUFFLE(2, 3, 0, 1)));
    return _mm_add_ps(s, _mm_shuffle_ps(s, s, _MM_SHUFFLE(1, 0, 3, 2)));
  }
  static MLIB_INLINE V eval(const V& va, const V& vb) {
    const __m128 a = va.m, b = vb.m;
    const __m128 d_ab_a = dp(a, _mm_sub_ps(b, a));
    const __m128 lhs = _mm_sub_ps(b, _mm_mul_ps(_mm_set1_ps(0.75f), a));
    const __m128 d_left = dp(lhs, _mm_mul_ps(b, d_ab_a));
    const __m128 right =
        _mm_mul_ps(_mm_mul_ps(_mm_mul_ps(_mm_set1_ps(1.0f / 400.0f), a), b), dp(a, b));
    return {_mm_add_ps(_mm_mul_ps(d_left, b), right)};
  }
};

struct Scalar4 {
  float x, y, z, w;
};
inline Scalar4 operator+(Scalar4 a, Scalar4 b) { return {a.x + b.x, a.y + b.y, a.z + b.z, a.w + b.w}; }
inline Scalar4 operator-(Scalar4 a, Scalar4 b) { return {a.x - b.x, a.y - b.y, a.z - b.z, a.w - b.w}; }
inline Scalar4 operator*(Scalar4 a, Scalar4 b) { return {a.x * b.x, a.y * b.y, a.z * b.z, a.w * b.w}; }
inline Scalar4 operator*(float s, Scalar4 a) { return {s * a.x, s * a.y, s * a.z, s * a.w}; }
inline Scalar4 operator*(Scalar4 a, float s) { return s * a; }
inline float dot(Scalar4 a, Scalar4 b) { return a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w; }

struct ScalarImpl {
  using V = Scalar4;
  static constexpr const char* name = "scalar";
  static V eval(const V& a, const V& b) {
    return dot(b - 0.75f * a, b * dot(a, b - a)) * b + (1.0f / 400.0f) * a * b * dot(a, b);
  }
};

float dot(const std::valarray<float>& a, const std::valarray<float>& b) { return (a * b).sum(); }

struct ValarrayImpl {
  using V = std::valarray<float>;
  static constexpr const char* name = "valarray";
  static V eval(const V& a, const V& b) {
    return dot(b - 0.75f * a, b * dot(a, b - a)) * b + (1.0f / 400.0f) * a * b * dot(a, b);
  }
};

// --- inputs and outputs ---------------------------------------------------------------
// "cycles" are TSC ticks. One timer lap covers a batch of up to --batch evaluations (a
// single evaluation of the fast forms is shorter than the cpuid fence itself); the fixed
// cost of an empty lap, measured first, is subtracted from every lap. For min, max and avg
// the figure is per evaluation (lap / batch); for sum it is the total over all iterations.
//
// The inputs cycle through 1024 random (a, b) pairs and every result is stored to an
// array that is checksummed at the end, so no work can be hoisted out of the timed loop.
template <class V>
V make(float x, float y, float z, float w);
template <>
mlib::vec4 make(float x, float y, float z, float w) { return mlib::vec4(x, y, z, w); }
template <>
M128 make(float x, float y, float z, float w) { return {_mm_setr_ps(x, y, z, w)}; }
template <>
Scalar4 make(float x, float y, float z, float w) { return {x, y, z, w}; }
template <>
std::valarray<float> make(float x, float y, float z, float w) { return {x, y, z, w}; }

float first_lane(const mlib::vec4& v) { return v[0]; }
float first_lane(const M128& v) { return _mm_cvtss_f32(v.m); }
float first_lane(const Scalar4& v) { return v.x; }
float first_lane(const std::valarray<float>& v) { return v[0]; }

struct Result {
  std::string impl;
  std::uint64_t iterations;
  double cycles[4];  // sum, min, max, avg (see "cycles" above)
};

constexpr mlib::Timer::Mode kModes[4] = {mlib::Timer::Mode::sum, mlib::Timer::Mode::min,
                                         mlib::Timer::Mode::max, mlib::Timer::Mode::avg};
constexpr const char* kModeNames[4] = {"sum", "min", "max", "avg"};

template <class Impl>
Result run(std::uint64_t iterations, std::uint64_t batch, double hz, std::uint64_t overhead,
           double& checksum) {
  using V = typename Impl::V;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<V> as, bs, out(kPool, make<V>(0, 0, 0, 0));
  for (std::size_t i = 0; i < kPool; ++i) {
    as.push_back(make<V>(u(rng), u(rng), u(rng), u(rng)));
    bs.push_back(make<V>(u(rng), u(rng), u(rng), u(rng)));
  }
  mlib::Timer lap(mlib::Timer::Mode::sum, hz), stats(mlib::Timer::Mode::sum, hz);
  std::uint64_t done = 0, k = 0;
  while (done < iterations) {
    const std::uint64_t n = std::min(batch, iterations - done);
    lap.Start();
    for (std::uint64_t i = 0; i < n; ++i, ++k) {
      const std::size_t j = k & (kPool - 1);
      out[j] = Impl::eval(as[j], bs[j]);
    }
    lap.Stop();
    asm volatile("" : : "r"(out.data()) : "memory");
    stats.Record(lap.Last() > overhead ? lap.Last() - overhead : 0);
    done += n;
  }
  for (const V& v : out) checksum += first_lane(v);
  Result r{Impl::name, iterations, {}};
  const double per_eval = static_cast<double>(std::min(batch, iterations));
  for (int m = 0; m < 4; ++m) {
    const double ticks = static_cast<double>(stats.Ticks(kModes[m]));
    r.cycles[m] = kModes[m] == mlib::Timer::Mode::sum ? ticks : ticks / per_eval;
  }
  return r;
}

// Median over all (mode, iterations) points of cycles(num) / cycles(den).
double median_ratio(const std::vector<Result>& rs, const std::string& num,
                    const std::string& den) {
  std::vector<double> ratios;
  for (const Result& a : rs) {
    if (a.impl != num) continue;
    for (const Result& b : rs) {
      if (b.impl != den || b.iterations != a.iterations) continue;
      for (int m = 0; m < 4; ++m)
        if (b.cycles[m] > 0) ratios.push_back(a.cycles[m] / b.cycles[m]);
    }
  }
  return bench::median(ratios);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bench_vec4: the thesis's table 2 (formula 11: vec4-ET, intrinsics, scalar, "
               "std::valarray)"};
  int max_exp = 7;
  std::uint64_t batch = 100;
  app.add_option("--max-exp", max_exp, "largest power of ten of iterations (1..8)")
      ->check(CLI::Range(1, 8));
  app.add_option("--batch", batch, "evaluations per timer lap (1..100000)")
      ->check(CLI::Range(1, 100000));
  CLI11_PARSE(app, argc, argv);

  const mlib::Timer probe;  // calibrates the TSC once
  const double hz = probe.Frequency();
  const std::uint64_t overhead = bench::empty_lap_ticks(hz);
  std::fprintf(stderr, "bench_vec4: TSC %.3f GHz, empty lap %llu ticks subtracted, batch %llu\n",
               hz * 1e-9, static_cast<unsigned long long>(overhead),
               static_cast<unsigned long long>(batch));

  std::vector<Result> results;
  double checksum = 0.0;
  std::uint64_t iterations = 1;
  for (int e = 1; e <= max_exp; ++e) {
    iterations *= 10;
    results.push_back(run<EtImpl>(iterations, batch, hz, overhead, checksum));
    results.push_back(run<IntrinsicsImpl>(iterations, batch, hz, overhead, checksum));
    results.push_back(
        run<IntrinsicsShuffleDotImpl>(iterations, batch, hz, overhead, checksum));
    results.push_back(run<ScalarImpl>(iterations, batch, hz, overhead, checksum));
    results.push_back(run<ValarrayImpl>(iterations, batch, hz, overhead, checksum));
  }

  std::printf("impl,mode,iterations,cycles\n");
  for (const Result& r : results)
    for (int m = 0; m < 4; ++m)
      std::printf("%s,%s,%llu,%.2f\n", r.impl.c_str(), kModeNames[m],
                  static_cast<unsigned long long>(r.iterations), r.cycles[m]);
  std::printf("et_vs_intrinsics=%.3f\n", median_ratio(results, "et", "intrinsics"));
  std::printf("valarray_vs_et=%.2f\n", median_ratio(results, "valarray", "et"));
  std::fprintf(stderr, "bench_vec4: (info) et_vs_intrinsics_shufdot=%.3f\n",
               median_ratio(results, "et", "intrinsics_shufdot"));
  std::fprintf(stderr, "bench_vec4: checksum %g\n", checksum);
  return 0;
}
