// rt2cpr/viewer/window.h — the viewer's window: SDL2 (a desktop's display, X11 or Wayland),
// its renderer, the image as a streaming texture, and Dear ImGui on SDL_Renderer, set up and
// torn down in order whatever happens.
#pragma once

#include <SDL.h>
#include <imgui.h>

#include <cstdint>
#include <string>

#include "rt2/image/image.h"
#include "rt2cpr/viewer/render_worker.h"

namespace rt2cpr::viewer {

class Window {
 public:
  // Throws rt2::Error "--interactive: ...: <SDL's reason>" when there is no display (only
  // X11 and Wayland are tried, unless SDL_VIDEODRIVER says otherwise: SDL would otherwise
  // fall back to drivers that show nothing) or the window cannot be made.
  Window(int width, int height, const std::string& title);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  SDL_Window* window() const { return window_; }
  SDL_Renderer* renderer() const { return renderer_; }
  // The event type the worker pushes when an image is ready (SDL_PushEvent is thread-safe).
  Uint32 frame_event() const { return frame_event_; }

  // The image's pixels into the streaming texture (recreated when the size changes).
  void upload(const Shown& s);
  // Clears, draws the image scaled to fit with the aspect of `aspect_w` x `aspect_h`, and the
  // panel's draw data when there is one (not yet presented).
  void draw(int aspect_w, int aspect_h, ImDrawData* panel);
  // What the window shows now (after draw, before present), as an image of display values.
  rt2::Image read_back() const;

 private:
  SDL_Window* window_ = nullptr;
  SDL_Renderer* renderer_ = nullptr;
  SDL_Texture* texture_ = nullptr;
  int texture_w_ = 0, texture_h_ = 0;
  Uint32 frame_event_ = 0;
};

}  // namespace rt2cpr::viewer
