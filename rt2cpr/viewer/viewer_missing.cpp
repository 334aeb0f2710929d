// rt2cpr/viewer/viewer_missing.cpp — the viewer of an rt2cpr built without SDL2 or Dear
// ImGui (SCons compiles this file instead of viewer.cpp then).
#include "rt2/base/error.h"
#include "rt2cpr/viewer/viewer.h"

namespace rt2cpr::viewer {

void run_interactive(const Options&) {
  throw rt2::Error("--interactive: this rt2cpr was built without the viewer; install "
                   "libsdl2-dev and libimgui-dev (scripts/test does) and build again");
}

bool available() { return false; }

}  // namespace rt2cpr::viewer
