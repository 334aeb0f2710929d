// rt2cpr/viewer/script.h — `--script FILE`: input for the viewer, read from a file, one
// command per line (the commands at ScriptCommand below), played through the same event
// path as a user's keys and mouse. Blank lines and lines starting with # are skipped.
// Numbers are checked here, names of keys and settings by the viewer before its window
// opens.
#pragma once

#include <string>
#include <vector>

namespace rt2cpr::viewer {

// The commands:
//   wait SECONDS          let time pass (the view keeps rendering)
//   key NAME [SECONDS]    press the key NAME (SDL's names, a blank written _: W, Left,
//                         F12, Left_Shift ...), hold it SECONDS (default: a tap), release it
//   mouse DX DY           move the mouse by (DX, DY) pixels with the right button held
//                         (mouse look)
//   scroll STEPS          turn the wheel STEPS notches (the movement speed)
//   screenshot PATH       write the image shown, as --output writes (extension: format)
//   window-shot PATH      write the window as shown, overlay included (read back from it)
//   wait-still [SECONDS]  wait until the still image has all its samples (default at most
//                         600 s; longer is an error)
//   set NAME VALUE        change a setting as the overlay does: depth, min-weight,
//                         subpixels, pattern, lights, triangle-test, threads, backend,
//                         overlay (on | off)
//   resize W H            resize the window
//   quit                  close the window (the script's end does not)
struct ScriptCommand {
  enum class Op { wait, key, mouse, scroll, screenshot, window_shot, wait_still, set, resize, quit };
  Op op = Op::wait;
  double seconds = 0.0;    // wait, key (0: a tap), wait-still
  double x = 0.0, y = 0.0;  // mouse DX DY, scroll STEPS (x), resize W H
  std::string name;        // key NAME, set NAME, screenshot / window-shot PATH
  std::string value;       // set VALUE
  int line = 0;            // in the file, for messages
};

// Reads `path`. Throws rt2::Error "path:line: problem" for an unknown command, a missing
// or extra argument, a number that is not one or out of range (seconds in [0, 86400], mouse
// and scroll within 1e6, sizes in [1, 16384]); "path: ..." for a file that cannot be read.
std::vector<ScriptCommand> read_script(const std::string& path);

}  // namespace rt2cpr::viewer
