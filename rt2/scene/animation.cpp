// rt2/scene/animation.cpp — sampling keyframe tracks (see animation.h).
#include "rt2/scene/animation.h"

#include <algorithm>
#include <cmath>

namespace rt2 {
namespace {

void normalize4(double* q) {
  const double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (int k = 0; k < 4; ++k) q[k] /= len;
}

// Spherical linear interpolation from key a to key b at u in [0, 1], along the shorter arc
// (glTF 2.0 Appendix C); nearly equal keys interpolate linearly. The keys are normalized
// first (glTF asks for unit keys; files hold rounded ones).
void slerp(const double* key_a, const double* key_b, double u, double* out) {
  double a[4] = {key_a[0], key_a[1], key_a[2], key_a[3]};
  double b[4] = {key_b[0], key_b[1], key_b[2], key_b[3]};
  normalize4(a);
  normalize4(b);
  double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
  const double sign = d < 0 ? -1.0 : 1.0;
  d *= sign;
  double wa = 1.0 - u, wb = u;
  if (d < 1.0 - 1e-9) {
    const double angle = std::acos(std::min(d, 1.0));
    const double s = std::sin(angle);
    wa = std::sin((1.0 - u) * angle) / s;
    wb = std::sin(u * angle) / s;
  }
  for (int k = 0; k < 4; ++k) out[k] = wa * a[k] + wb * sign * b[k];
  normalize4(out);
}

}  // namespace

void sample(const Track& track, double seconds, double* out) {
  const int w = track.width;
  const std::size_t keys = track.times.size();
  const bool cubic = track.interpolation == Interpolation::cubic_spline;
  // Key k's value (the middle group of a cubic key).
  const auto value = [&](std::size_t k) {
    return track.values.data() + (cubic ? (3 * k + 1) * std::size_t(w) : k * std::size_t(w));
  };
  const auto finish = [&] {
    if (track.property == NodeProperty::rotation) normalize4(out);
  };
  if (keys == 0) return;
  // The key interval [k, k + 1] holding `seconds`, or the end it lies beyond.
  const auto after = std::upper_bound(track.times.begin(), track.times.end(), seconds);
  if (after == track.times.begin() || after == track.times.end() || !(seconds == seconds)) {
    const std::size_t k = after == track.times.begin() || !(seconds == seconds) ? 0 : keys - 1;
    std::copy(value(k), value(k) + w, out);
    return finish();
  }
  const std::size_t k = std::size_t(after - track.times.begin()) - 1;
  const double t0 = track.times[k], t1 = track.times[k + 1], dt = t1 - t0;
  const double u = (seconds - t0) / dt;
  switch (track.interpolation) {
    case Interpolation::step:
      std::copy(value(k), value(k) + w, out);
      return finish();
    case Interpolation::linear:
      if (track.property == NodeProperty::rotation) return slerp(value(k), value(k + 1), u, out);
      for (int c = 0; c < w; ++c) out[c] = value(k)[c] + u * (value(k + 1)[c] - value(k)[c]);
      return;
    case Interpolation::cubic_spline: {
      // Hermite basis; the tangents are per second, so they scale with the interval.
      const double u2 = u * u, u3 = u2 * u;
      const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2,
                   h11 = u3 - u2;
      const double* out_tangent = value(k) + w;
      const double* in_tangent = value(k + 1) - w;
      for (int c = 0; c < w; ++c)
        out[c] = h00 * value(k)[c] + h10 * dt * out_tangent[c] + h01 * value(k + 1)[c] +
                 h11 * dt * in_tangent[c];
      return finish();
    }
  }
}

double Animation::duration() const {
  double end = 0.0;
  for (const Channel& c : channels)
    if (!c.track.times.empty()) end = std::max(end, c.track.times.back());
  return end;
}

void Animation::pose(double seconds, std::vector<NodeTrs>& trs) const {
  for (const Channel& c : channels) {
    if (c.node < 0 || std::size_t(c.node) >= trs.size()) continue;
    NodeTrs& n = trs[std::size_t(c.node)];
    switch (c.track.property) {
      case NodeProperty::translation: sample(c.track, seconds, n.translation.data()); break;
      case NodeProperty::rotation: sample(c.track, seconds, n.rotation.data()); break;
      case NodeProperty::scale: sample(c.track, seconds, n.scale.data()); break;
      case NodeProperty::weights:
        n.weights.resize(std::size_t(c.track.width));
        sample(c.track, seconds, n.weights.data());
        break;
    }
  }
}

Matrix4d operator*(const Matrix4d& a, const Matrix4d& b) {
  Matrix4d r{};
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += a[k * 4 + row] * b[c * 4 + k];
      r[c * 4 + row] = s;
    }
  return r;
}

Matrix4d matrix_of(const NodeTrs& trs) {
  Matrix4d t = kIdentity4d, s = kIdentity4d;
  std::copy(trs.translation.begin(), trs.translation.end(), t.begin() + 12);
  double q[4] = {trs.rotation[0], trs.rotation[1], trs.rotation[2], trs.rotation[3]};
  normalize4(q);
  const double x = q[0], y = q[1], z = q[2], w = q[3];
  // clang-format off
  const Matrix4d r = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),     0,
                      2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),     0,
                      2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y), 0,
                      0,                       0,                       0,                       1};
  // clang-format on
  s[0] = trs.scale[0], s[5] = trs.scale[1], s[10] = trs.scale[2];
  return t * r * s;
}

}  // namespace rt2
