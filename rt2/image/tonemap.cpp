// rt2/image/tonemap.cpp — the tone curves (see tonemap.h).
#include "rt2/image/tonemap.h"

#include <cmath>

namespace rt2 {

float tonemap(float c, const Display& d) {
  if (d.exposure != 0.0f) c *= std::exp2(d.exposure);
  switch (d.curve) {
    case ToneCurve::none:
      return c;
    case ToneCurve::reinhard:
      if (c == INFINITY) return 1.0f;
      return c > 0.0f ? c / (1.0f + c) : (c == c ? 0.0f : c);
    case ToneCurve::aces: {
      if (c == INFINITY) return 1.0f;
      if (!(c > 0.0f)) return c == c ? 0.0f : c;
      const float y = c * (2.51f * c + 0.03f) / (c * (2.43f * c + 0.59f) + 0.14f);
      return y < 1.0f ? y : 1.0f;
    }
  }
  return c;
}

void tonemap(std::vector<float>& rgb, const Display& d) {
  if (d.is_identity()) return;
  for (float& v : rgb) v = tonemap(v, d);
}

const char* tone_curve_name(ToneCurve c) {
  switch (c) {
    case ToneCurve::reinhard: return "reinhard";
    case ToneCurve::aces: return "aces";
    default: return "none";
  }
}

bool parse_tone_curve(const std::string& name, ToneCurve& c) {
  for (const ToneCurve t : {ToneCurve::none, ToneCurve::reinhard, ToneCurve::aces})
    if (name == tone_curve_name(t)) {
      c = t;
      return true;
    }
  return false;
}

}  // namespace rt2
