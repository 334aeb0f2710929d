// rt2cpr/viewer/script_player.h — plays a script (script.h) into the viewer: keys, mouse
// and wheel become SDL events pushed onto SDL's queue, where the window reads them as it
// reads a user's; the rest (screenshots, settings, resizing) is handed to the viewer.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "rt2cpr/viewer/script.h"

namespace rt2cpr::viewer {

class ScriptPlayer {
 public:
  // Throws rt2::Error "path:line: ..." for a key name SDL does not know.
  ScriptPlayer(std::vector<ScriptCommand> script, std::string path);

  // Plays the next command if it is due at `now` (seconds since the window opened): pushes
  // the events of key, mouse, scroll and quit and returns nothing, or returns the command
  // for the viewer to carry out. At most one command per call, so that the events it
  // pushed are read before the next one looks at the view. `converged`: the image shown is
  // the converged still of the current view (wait-still waits for it; past its time it
  // throws rt2::Error "path:line: ..."); `failure`: why the current view cannot be rendered,
  // or empty (wait-still then throws at once, with it).
  std::optional<ScriptCommand> step(double now, bool converged, const std::string& failure = {});

  bool done() const { return next_ == script_.size() && !key_down_; }
  // "path:line: " of the command played last, for the viewer's messages.
  std::string where(const ScriptCommand& c) const;

 private:
  std::vector<ScriptCommand> script_;
  std::string path_;
  std::size_t next_ = 0;
  double ready_at_ = 0.0;       // the next command waits until then
  double started_at_ = -1.0;    // when the command under way began (wait-still)
  bool key_down_ = false;       // a held key to release at ready_at_
  int key_scancode_ = 0;
};

// SDL's scancode for a script's key name ('_' for a blank), or 0 when unknown.
int scancode_of(const std::string& name);

}  // namespace rt2cpr::viewer
