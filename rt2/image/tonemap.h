// rt2/image/tonemap.h — from scene radiance to display values: exposure and a tone curve.
//
// A renderer's linear values are unbounded (a light, an environment's sun, a bright
// highlight), while a display format holds [0, 1]. Display formats (PNG, JPEG, PPM, ...)
// therefore get each channel scaled by the exposure, 2^stops, and mapped by a curve
// (ToneCurve below) before the sRGB encoding (image_io.h); float formats (EXR, HDR, TIFF)
// keep the linear values whatever these settings say, so nothing is lost for later grading.
#pragma once

#include <string>
#include <vector>

namespace rt2 {

//   none      c' = c (clamped to [0, 1] by the encoding), the default
//   reinhard  c' = c / (1 + c)                       (Reinhard et al. 2002, per channel)
//   aces      c' = c (2.51 c + 0.03) / (c (2.43 c + 0.59) + 0.14), clamped to [0, 1]
//             (Narkowicz's 2015 fit of the ACES filmic reference curve, per channel)
// NaN stays NaN (the encoding writes it as 0); +inf maps to 1.
enum class ToneCurve { none, reinhard, aces };

struct Display {
  ToneCurve curve = ToneCurve::none;
  float exposure = 0.0f;  // stops: values are scaled by 2^exposure before the curve
  bool is_identity() const { return curve == ToneCurve::none && exposure == 0.0f; }
};

// One linear value through the exposure and the curve.
float tonemap(float linear, const Display& display);

// Every value of `rgb` through tonemap (in place).
void tonemap(std::vector<float>& rgb, const Display& display);

// "none", "reinhard", "aces"; parse_tone_curve returns false for any other name.
const char* tone_curve_name(ToneCurve c);
bool parse_tone_curve(const std::string& name, ToneCurve& c);

}  // namespace rt2
