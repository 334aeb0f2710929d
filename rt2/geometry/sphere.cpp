// rt2/geometry/sphere.cpp — the double-precision ray/sphere test (see sphere.h).
#include "rt2/geometry/sphere.h"

#include <utility>

namespace rt2::detail {

bool intersect_sphere_double(const Sphere& s, const Ray& r, float t_min, float t_max, float& t) {
  double oc[3], d[3];
  for (int i = 0; i < 3; ++i) {
    oc[i] = double(r.org[i]) - double(s.center[i]);
    d[i] = r.dir[i];
  }
  const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  const double b = (oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2]) / dd;
  double perp2 = 0.0, oc2 = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double p = oc[i] - b * d[i];
    perp2 += p * p;
    oc2 += oc[i] * oc[i];
  }
  const double r2 = double(s.radius) * s.radius;
  const double disc = r2 - perp2 * dd;
  if (!(disc >= 0.0)) return false;
  const double q = -(b * dd + std::copysign(std::sqrt(disc * dd), b));
  double t0 = (oc2 - r2) / q, t1 = q / dd;
  if (t0 > t1) std::swap(t0, t1);
  for (const double root : {t0, t1})
    if (root > t_min && root < t_max) {
      t = static_cast<float>(root);
      return t > t_min && t < t_max;
    }
  return false;
}

}  // namespace rt2::detail
