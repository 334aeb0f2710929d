// rt2cpr/viewer/controls.h — what the viewer's user can change while it runs, from the
// overlay or a script's `set NAME VALUE`: the render settings, the threads, the lights.
#pragma once

#include <string>

#include "rt2/render/renderer.h"
#include "rt2/render/schedule.h"

namespace rt2cpr::viewer {

struct Controls {
  rt2::RenderSettings settings;  // the converged image's
  rt2::Schedule schedule;
  int lights = -1;               // total lights; -1: the scene's own
  bool overlay = true;           // the panel is shown
};

// `set NAME VALUE`: depth, min-weight, subpixels, pattern (grid | circle), lights,
// triangle-test (fast | watertight), threads, backend (serial | omp | tbb), overlay (on |
// off). Throws rt2::Error with a one-line message for an unknown name or a bad value; the
// controls are unchanged then.
void set_control(Controls& c, const std::string& name, const std::string& value);

}  // namespace rt2cpr::viewer
