// rt2cpr/viewer/viewer.h — `rt2cpr --interactive`: a window (SDL2) that shows the scene as
// it renders, flown through with keys and mouse, with a panel (Dear ImGui) of figures and
// settings; while the camera moves it shows quick frames of one sample per pixel (at a lower
// resolution when they come slower than --target-fps), and when it stops the image refines
// pass by pass into exactly what a file render gives (render_worker.h).
#pragma once

#include "rt2cpr/options.h"

namespace rt2cpr::viewer {

// Opens the window and runs until it is closed, Esc is pressed or the script quits.
// Throws rt2::Error with a one-line message for no display, a bad script, a scene that
// cannot be rendered, or a script command that fails (a screenshot that cannot be written,
// an image that does not converge in time).
void run_interactive(const Options& o);

// Whether this rt2cpr was built with the viewer (SDL2 and Dear ImGui found by SCons).
bool available();

}  // namespace rt2cpr::viewer
