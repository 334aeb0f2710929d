// rt2cpr/viewer/overlay.h — the viewer's panel (Dear ImGui): what is rendered and how
// fast, and the controls (controls.h) to change it.
#pragma once

#include <string>

#include "rt2/base/isa.h"
#include "rt2/render/renderer.h"
#include "rt2cpr/viewer/controls.h"

namespace rt2cpr::viewer {

struct OverlayInfo {
  double fps = 0.0;           // images shown per second, lately
  double render_ms = 0.0;     // rendering the last one
  rt2::RayCounts rays;        // its rays
  rt2::Isa isa = rt2::Isa::sse41;
  int width = 0, height = 0;  // the last image's size
  int scale = 1;              // the moving frames' resolution divisor
  bool moving = false;
  int pass = 0, passes = 1;   // the still's
  float speed = 1.0f;         // movement, units per second
  std::string error;          // the last error, or empty
  std::string screenshot_key = "F12";
};

// Draws the panel inside an ImGui frame; true when the user changed a control.
bool draw_overlay(Controls& c, const OverlayInfo& info);

}  // namespace rt2cpr::viewer
