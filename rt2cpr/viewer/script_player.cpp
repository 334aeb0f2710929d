// rt2cpr/viewer/script_player.cpp — a script's commands as SDL events.
#include "rt2cpr/viewer/script_player.h"

#include <SDL.h>

#include <algorithm>
#include <cmath>

#include "rt2/base/error.h"
#include "rt2cpr/viewer/controls.h"

namespace rt2cpr::viewer {

namespace {

using Op = ScriptCommand::Op;

void push_key(int scancode, bool down) {
  SDL_Event e{};
  e.type = down ? SDL_KEYDOWN : SDL_KEYUP;
  e.key.timestamp = SDL_GetTicks();
  e.key.state = down ? SDL_PRESSED : SDL_RELEASED;
  e.key.keysym.scancode = SDL_Scancode(scancode);
  e.key.keysym.sym = SDL_GetKeyFromScancode(SDL_Scancode(scancode));
  SDL_PushEvent(&e);
}

}  // namespace

int scancode_of(const std::string& name) {
  std::string sdl = name;
  std::replace(sdl.begin(), sdl.end(), '_', ' ');
  return int(SDL_GetScancodeFromName(sdl.c_str()));
}

ScriptPlayer::ScriptPlayer(std::vector<ScriptCommand> script, std::string path)
    : script_(std::move(script)), path_(std::move(path)) {
  for (const ScriptCommand& c : script_) {
    if (c.op == Op::key && scancode_of(c.name) == SDL_SCANCODE_UNKNOWN)
      throw rt2::Error(where(c) + "unknown key '" + c.name +
                       "' (SDL's key names, a blank written _: W, Left, F12, Left_Shift ...)");
    if (c.op == Op::set) {  // each name and value on its own, before the window opens
      Controls scratch;
      try {
        set_control(scratch, c.name, c.value);
      } catch (const rt2::Error& e) {
        throw rt2::Error(where(c) + e.what());
      }
    }
  }
}

std::string ScriptPlayer::where(const ScriptCommand& c) const {
  return path_ + ":" + std::to_string(c.line) + ": ";
}

std::optional<ScriptCommand> ScriptPlayer::step(double now, bool converged, const std::string& failure) {
  if (now < ready_at_) return std::nullopt;
  if (key_down_) {  // the hold is over
    push_key(key_scancode_, false);
    key_down_ = false;
    return std::nullopt;
  }
  if (next_ == script_.size()) return std::nullopt;
  const ScriptCommand& c = script_[next_];
  if (c.op == Op::wait_still) {
    if (started_at_ < 0.0) started_at_ = now;
    if (!converged) {
      if (!failure.empty()) throw rt2::Error(where(c) + "the image cannot converge: " + failure);
      if (now - started_at_ > c.seconds)
        throw rt2::Error(where(c) + "the image did not converge within " +
                         std::to_string(int(std::ceil(c.seconds))) + " s");
      return std::nullopt;
    }
    started_at_ = -1.0;
    ++next_;
    return std::nullopt;
  }
  ++next_;
  switch (c.op) {
    case Op::wait: ready_at_ = now + c.seconds; return std::nullopt;
    case Op::key:
      key_scancode_ = scancode_of(c.name);
      push_key(key_scancode_, true);
      key_down_ = true;  // released at the next call past the hold (a tap: the next call)
      ready_at_ = now + c.seconds;
      return std::nullopt;
    case Op::mouse: {
      SDL_Event e{};
      e.type = SDL_MOUSEMOTION;
      e.motion.timestamp = SDL_GetTicks();
      e.motion.state = SDL_BUTTON_RMASK;
      SDL_GetMouseState(&e.motion.x, &e.motion.y);  // where the pointer is
      e.motion.xrel = int(std::lround(c.x));
      e.motion.yrel = int(std::lround(c.y));
      SDL_PushEvent(&e);
      return std::nullopt;
    }
    case Op::scroll: {
      SDL_Event e{};
      e.type = SDL_MOUSEWHEEL;
      e.wheel.timestamp = SDL_GetTicks();
      e.wheel.y = int(std::lround(c.x));
      SDL_PushEvent(&e);
      return std::nullopt;
    }
    case Op::quit: {
      SDL_Event e{};
      e.type = SDL_QUIT;
      SDL_PushEvent(&e);
      return std::nullopt;
    }
    default: return c;  // screenshot, window-shot, set, resize: the viewer's
  }
}

}  // namespace rt2cpr::viewer
