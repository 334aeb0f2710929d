// rt2cpr/viewer/window.cpp — SDL2 and Dear ImGui's SDL backends.
#include "rt2cpr/viewer/window.h"

#include <imgui_impl_sdl.h>
#include <imgui_impl_sdlrenderer.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "rt2/base/error.h"
#include "rt2/image/srgb.h"

namespace rt2cpr::viewer {

namespace {

[[noreturn]] void sdl_failed(const char* what) {
  throw rt2::Error(std::string("--interactive: ") + what + ": " + SDL_GetError());
}

}  // namespace

Window::Window(int width, int height, const std::string& title) {
  // A desktop's display only: without one SDL would fall back to drivers that show
  // nothing (offscreen, a console's framebuffer), and the viewer would run unseen. A user
  // who sets SDL_VIDEODRIVER chooses for themselves.
  if (!std::getenv("SDL_VIDEODRIVER")) {
    const auto set = [](const char* name) { return std::getenv(name) && *std::getenv(name); };
    std::string drivers = set("DISPLAY") ? "x11" : "";
    if (set("WAYLAND_DISPLAY")) drivers += drivers.empty() ? "wayland" : ",wayland";
    SDL_SetHint(SDL_HINT_VIDEODRIVER, drivers.c_str());
  }
  if (SDL_Init(SDL_INIT_VIDEO) != 0) {
    std::string which;
    for (const char* name : {"DISPLAY", "WAYLAND_DISPLAY"})
      if (std::getenv(name) && *std::getenv(name))
        which += std::string(which.empty() ? "" : ", ") + name + "=" + std::getenv(name);
    sdl_failed(("no display could be opened (" + which + ")").c_str());
  }
  window_ = SDL_CreateWindow(title.c_str(), SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED,
                             width, height, SDL_WINDOW_RESIZABLE | SDL_WINDOW_ALLOW_HIGHDPI);
  if (!window_) sdl_failed("the window could not be created");
  renderer_ = SDL_CreateRenderer(window_, -1, SDL_RENDERER_ACCELERATED);
  if (!renderer_) renderer_ = SDL_CreateRenderer(window_, -1, SDL_RENDERER_SOFTWARE);
  if (!renderer_) sdl_failed("no renderer for the window");
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the user's folder
  ImGui::StyleColorsDark();
  ImGui_ImplSDL2_InitForSDLRenderer(window_);
  ImGui_ImplSDLRenderer_Init(renderer_);
  frame_event_ = SDL_RegisterEvents(1);
}

Window::~Window() {
  if (texture_) SDL_DestroyTexture(texture_);
  ImGui_ImplSDLRenderer_Shutdown();
  ImGui_ImplSDL2_Shutdown();
  ImGui::DestroyContext();
  SDL_DestroyRenderer(renderer_);
  SDL_DestroyWindow(window_);
  SDL_Quit();
}

void Window::upload(const Shown& s) {
  const int w = s.image.width, h = s.image.height;
  if (!texture_ || w != texture_w_ || h != texture_h_) {
    if (texture_) SDL_DestroyTexture(texture_);
    texture_ = SDL_CreateTexture(renderer_, SDL_PIXELFORMAT_RGBA32, SDL_TEXTUREACCESS_STREAMING, w, h);
    if (!texture_) sdl_failed("no texture for the image");
    texture_w_ = w;
    texture_h_ = h;
  }
  SDL_UpdateTexture(texture_, nullptr, s.pixels.data(), w * 4);
}

void Window::draw(int aspect_w, int aspect_h, ImDrawData* panel) {
  SDL_SetRenderDrawColor(renderer_, 0, 0, 0, 255);
  SDL_RenderClear(renderer_);
  if (texture_) {
    int ww = 0, wh = 0;
    SDL_GetRendererOutputSize(renderer_, &ww, &wh);
    const double s = std::min(double(ww) / aspect_w, double(wh) / aspect_h);
    const int dw = std::max(1, int(std::lround(aspect_w * s)));
    const int dh = std::max(1, int(std::lround(aspect_h * s)));
    const SDL_Rect dst{(ww - dw) / 2, (wh - dh) / 2, dw, dh};
    SDL_RenderCopy(renderer_, texture_, nullptr, &dst);
  }
  if (panel) ImGui_ImplSDLRenderer_RenderDrawData(panel);
}

rt2::Image Window::read_back() const {
  int ww = 0, wh = 0;
  SDL_GetRendererOutputSize(renderer_, &ww, &wh);
  std::vector<std::uint8_t> rgba(std::size_t(ww) * std::size_t(wh) * 4);
  if (SDL_RenderReadPixels(renderer_, nullptr, SDL_PIXELFORMAT_RGBA32, rgba.data(), ww * 4) != 0)
    sdl_failed("the window could not be read back");
  rt2::Image img(ww, wh);
  for (std::size_t p = 0; p < std::size_t(ww) * std::size_t(wh); ++p)
    for (std::size_t c = 0; c < 3; ++c)  // decoded: written back as 8-bit sRGB, the same values
      img.rgb[p * 3 + c] = rt2::srgb_decode(float(rgba[p * 4 + c]) / 255.0f);
  return img;
}

}  // namespace rt2cpr::viewer
