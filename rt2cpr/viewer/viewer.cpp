// rt2cpr/viewer/viewer.cpp — the window: SDL2 for the window, input and a streaming
// texture, Dear ImGui for the panel; the images come from the RenderWorker's thread.
//
// The window's thread never renders: each turn of its loop reads the input (a user's, or a
// script's pushed onto the same queue), moves the camera by the time passed, asks the worker
// for the newest view, and shows the newest image when one has come. It sleeps in
// SDL_WaitEventTimeout between turns; the worker wakes it with an event when an image is
// ready.
#include "rt2cpr/viewer/viewer.h"

#include <SDL.h>
#include <imgui.h>
#include <imgui_impl_sdl.h>
#include <imgui_impl_sdlrenderer.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <vector>

#include "rt2/base/error.h"
#include "rt2/image/image_io.h"
#include "rt2/image/output_file.h"
#include "rt2/image/srgb.h"
#include "rt2cpr/scene_setup.h"
#include "rt2cpr/viewer/controls.h"
#include "rt2cpr/viewer/fly_camera.h"
#include "rt2cpr/viewer/frame_log.h"
#include "rt2cpr/viewer/overlay.h"
#include "rt2cpr/viewer/render_worker.h"
#include "rt2cpr/viewer/resolution_scaler.h"
#include "rt2cpr/viewer/script_player.h"
#include "rt2cpr/viewer/window.h"

namespace rt2cpr::viewer {

namespace {

using Clock = std::chrono::steady_clock;

// The camera counts as moving until this long after its last change.
constexpr double kSettleSeconds = 0.12;

// The next free rt2cpr-N.png in the current folder.
std::string next_screenshot_name() {
  for (int n = 1;; ++n) {
    const std::string name = "rt2cpr-" + std::to_string(n) + ".png";
    std::error_code ec;
    if (!std::filesystem::exists(name, ec)) return name;
  }
}

class Viewer {
 public:
  // `scene`: the options' scene and `poser` its poser (rt2cpr/scene_setup.h load_scene). Compiles it before the
  // window opens, so that a scene that cannot be rendered is one error line and no window.
  Viewer(const Options& o, rt2::Scene scene, rt2::ScenePoser poser,
         std::optional<ScriptPlayer> script, SDL_Keycode screenshot_key)
      : o_(o),
        script_(std::move(script)),
        screenshot_key_(screenshot_key),
        start_camera_(scene.camera),
        animated_(scene.animation >= 0),
        duration_(animated_ ? scene.animations[std::size_t(scene.animation)].duration : 0.0),
        playing_(duration_ > 0.0),
        seconds_(o.pose.seconds),
        fly_(start_camera_, speed_for(scene)),
        scaler_(o.interactive.target_fps) {
    controls_.settings = o.render;
    controls_.settings.passes = 1;
    controls_.schedule = o.schedule;
    controls_.lights = o.lights;
    // The worker pushes an event when an image is ready; it renders only when asked, after
    // the window exists.
    worker_.emplace(
        std::move(scene), o,
        [this] {
          SDL_Event e{};
          e.type = window_->frame_event();
          SDL_PushEvent(&e);
        },
        std::move(poser));
    window_.emplace(o.render.width, o.render.height,
                    "rt2 — " + (o.scene.empty() ? std::string("built-in scene") : o.scene));
    t0_ = Clock::now();
  }

  // A quarter of the scene's diagonal per second.
  static float speed_for(const rt2::Scene& scene) {
    const rt2::Aabb box = scene.bounds();
    const float diagonal = box.is_empty() ? 0.0f : calc_distance(box.hi, box.lo);
    return std::isfinite(diagonal) && diagonal > 0.0f ? 0.25f * diagonal : 1.0f;
  }

  void run() {
    double last = now();
    while (!quit_) {
      pump_events(busy() ? 4 : 50);
      const double t = now();
      move_camera(t - last);
      if (playing_) {  // an animated scene plays in real time, over and over
        seconds_ += t - last;
        if (duration_ > 0.0 && seconds_ > duration_) seconds_ = std::fmod(seconds_, duration_);
        changed();
      }
      last = t;
      ask_worker(t);
      take_image(t);
      if (script_) play_script(t);
      take_error();
      if (redraw_ > 0 || window_shot_) present();
    }
    finish();
  }

 private:
  double now() const { return std::chrono::duration<double>(Clock::now() - t0_).count(); }
  bool moving_keys() const {
    for (int i = 0; i < SDL_NUM_SCANCODES; ++i)
      if (held_[std::size_t(i)] && movement(SDL_Scancode(i)).any) return true;
    return false;
  }
  // Something is changing: turn the loop quickly.
  bool busy() const {
    return moving_keys() || now() - last_change_ < kSettleSeconds + 0.05 || (script_ && !script_->done());
  }

  struct Move {
    bool any = false;
    float forward = 0, right = 0, up = 0;
  };
  static Move movement(SDL_Scancode k) {
    switch (k) {
      case SDL_SCANCODE_W: case SDL_SCANCODE_UP: return {true, 1, 0, 0};
      case SDL_SCANCODE_S: case SDL_SCANCODE_DOWN: return {true, -1, 0, 0};
      case SDL_SCANCODE_D: case SDL_SCANCODE_RIGHT: return {true, 0, 1, 0};
      case SDL_SCANCODE_A: case SDL_SCANCODE_LEFT: return {true, 0, -1, 0};
      case SDL_SCANCODE_E: case SDL_SCANCODE_PAGEUP: return {true, 0, 0, 1};
      case SDL_SCANCODE_Q: case SDL_SCANCODE_PAGEDOWN: return {true, 0, 0, -1};
      default: return {};
    }
  }

  void pump_events(int timeout_ms) {
    SDL_Event e;
    if (!SDL_WaitEventTimeout(&e, timeout_ms)) return;
    do handle(e);
    while (SDL_PollEvent(&e));
  }

  // The view changed: the worker is asked for it; the window is drawn again when its
  // image comes (drawing on every turn of the loop would take the CPU from rendering).
  void changed() {
    last_change_ = now();
    ++generation_;
  }

  void handle(const SDL_Event& e) {
    ImGui_ImplSDL2_ProcessEvent(&e);
    const ImGuiIO& io = ImGui::GetIO();
    switch (e.type) {
      case SDL_QUIT: quit_ = true; break;
      case SDL_WINDOWEVENT:
        if (e.window.event == SDL_WINDOWEVENT_CLOSE) quit_ = true;
        redraw_ = std::max(redraw_, 1);
        break;
      case SDL_KEYDOWN:
        redraw_ = 2;
        if (io.WantCaptureKeyboard) break;
        held_[std::size_t(e.key.keysym.scancode)] = true;
        if (e.key.repeat) break;
        if (e.key.keysym.sym == screenshot_key_) {
          save_screenshot();
          break;
        }
        switch (e.key.keysym.sym) {
          case SDLK_r:
            fly_ = FlyCamera(start_camera_, fly_.speed());
            changed();
            break;
          case SDLK_c:
            std::fputs(fly_.toml().c_str(), stdout);
            std::fflush(stdout);
            break;
          case SDLK_SPACE:  // play or pause an animated scene
            if (!(duration_ > 0.0)) break;
            playing_ = !playing_;
            changed();
            break;
          case SDLK_COMMA:  // a frame (1 / --fps) back or on, paused
          case SDLK_PERIOD:
            if (!animated_) break;
            playing_ = false;
            seconds_ += (e.key.keysym.sym == SDLK_COMMA ? -1.0 : 1.0) / o_.fps;
            changed();
            break;
          case SDLK_F1:
            controls_.overlay = !controls_.overlay;
            redraw_ = std::max(redraw_, 1);
            break;
          case SDLK_ESCAPE: quit_ = true; break;
          default: break;
        }
        break;
      case SDL_KEYUP: held_[std::size_t(e.key.keysym.scancode)] = false; break;
      case SDL_MOUSEBUTTONDOWN:
        panel_drag_ = io.WantCaptureMouse;
        redraw_ = 2;
        break;
      case SDL_MOUSEBUTTONUP:
        panel_drag_ = false;
        redraw_ = 2;
        break;
      case SDL_TEXTINPUT: redraw_ = 2; break;
      case SDL_MOUSEMOTION:
        if ((e.motion.state & (SDL_BUTTON_LMASK | SDL_BUTTON_RMASK)) && !panel_drag_) {
          fly_.turn(float(e.motion.xrel), float(e.motion.yrel));
          changed();
        } else if (controls_.overlay) {
          redraw_ = 2;  // the panel follows the pointer
        }
        break;
      case SDL_MOUSEWHEEL:
        if (!io.WantCaptureMouse) fly_.scale_speed(float(e.wheel.y));
        redraw_ = std::max(redraw_, 1);
        break;
      default:
        if (e.type == window_->frame_event()) redraw_ = std::max(redraw_, 1);
        break;
    }
  }

  void move_camera(double seconds) {
    Move m;
    for (int i = 0; i < SDL_NUM_SCANCODES; ++i) {
      if (!held_[std::size_t(i)]) continue;
      const Move k = movement(SDL_Scancode(i));
      m.any |= k.any;
      m.forward += k.forward;
      m.right += k.right;
      m.up += k.up;
    }
    if (!m.any) return;
    const bool fast = held_[SDL_SCANCODE_LSHIFT] || held_[SDL_SCANCODE_RSHIFT];
    const float s = float(std::min(seconds, 0.25)) * (fast ? 4.0f : 1.0f);
    fly_.move(std::clamp(m.forward, -1.0f, 1.0f), std::clamp(m.right, -1.0f, 1.0f),
              std::clamp(m.up, -1.0f, 1.0f), s);
    changed();
  }

  void ask_worker(double t) {
    const bool moving = t - last_change_ < kSettleSeconds;
    if (moving != moving_) {
      moving_ = moving;
      ++generation_;
      if (moving) scaler_.restart();
    }
    ViewRequest r;
    r.camera = fly_.camera();
    r.settings = controls_.settings;
    r.schedule = controls_.schedule;
    r.lights = controls_.lights;
    r.seconds = seconds_;
    r.moving = moving;
    r.scale = scaler_.scale();
    r.generation = generation_;
    worker_->request(r);
  }

  void take_image(double t) {
    Shown s;
    if (!worker_->take(s)) return;
    window_->upload(s);
    // The renderer's time for this frame: since the last one shown, less its wait for work.
    const double busy = t - shown_at_ - s.idle_ms * 1e-3;
    if (s.moving && shown_ && shown_->moving) scaler_.add(busy);
    // Images per second the renderer delivers, smoothed over the last few.
    if (shown_ && busy > 0.0) rate_ = rate_ > 0.0 ? 0.8 * rate_ + 0.2 / busy : 1.0 / busy;
    shown_at_ = t;
    log_.add({t, s.moving, s.pass, s.passes, s.image.width, s.image.height, s.ms, s.rays.total()});
    shown_ = std::move(s);
    redraw_ = std::max(redraw_, 1);
  }

  bool converged() const { return shown_ && shown_->converged() && shown_->generation == generation_; }

  // The worker's failures: each new message printed once (a failing setting fails every
  // request, many a second while moving), and kept for the panel and the script.
  void take_error() {
    std::optional<RenderWorker::Failure> f = worker_->take_error();
    if (!f) return;
    if (!error_ || error_->message != f->message)
      std::fprintf(stderr, "rt2cpr: %s\n", f->message.c_str());
    error_ = std::move(f);
    redraw_ = std::max(redraw_, 1);
  }

  void play_script(double t) {
    const bool failed = error_ && error_->generation == generation_;
    const std::optional<ScriptCommand> c =
        script_->step(t, converged(), failed ? error_->message : std::string());
    if (!c) return;
    using Op = ScriptCommand::Op;
    switch (c->op) {
      case Op::screenshot:
        if (!shown_) throw rt2::Error(script_->where(*c) + "no image has been shown yet");
        rt2::write_image(c->name, shown_->image, o_.display);
        if (!o_.quiet) std::printf("wrote %s\n", c->name.c_str());
        break;
      case Op::window_shot: window_shot_ = c->name; break;
      case Op::set:
        try {
          set_control(controls_, c->name, c->value);
        } catch (const rt2::Error& e) {
          throw rt2::Error(script_->where(*c) + e.what());
        }
        changed();
        break;
      case Op::resize:
        SDL_SetWindowSize(window_->window(), int(c->x), int(c->y));
        redraw_ = std::max(redraw_, 1);
        break;
      default: break;
    }
  }

  void save_screenshot() {
    if (!shown_) return;
    const std::string path = o_.output.empty() ? next_screenshot_name() : o_.output;
    try {
      rt2::write_image(path, shown_->image, o_.display);
      if (!o_.quiet) std::printf("wrote %s\n", path.c_str());
    } catch (const rt2::Error& e) {  // the session goes on
      std::fprintf(stderr, "rt2cpr: %s\n", e.what());
    }
  }

  void present() {
    redraw_ = std::max(0, redraw_ - 1);
    ImGui_ImplSDLRenderer_NewFrame();
    ImGui_ImplSDL2_NewFrame();
    ImGui::NewFrame();
    if (controls_.overlay) {
      OverlayInfo info;
      info.fps = rate_;
      info.isa = o_.isa;
      info.scale = scaler_.scale();
      info.speed = fly_.speed();
      info.error = error_ ? error_->message : std::string();
      info.screenshot_key = SDL_GetKeyName(screenshot_key_);
      if (shown_) {
        info.render_ms = shown_->ms;
        info.rays = shown_->rays;
        info.width = shown_->image.width;
        info.height = shown_->image.height;
        info.moving = shown_->moving;
        info.pass = shown_->pass;
        info.passes = shown_->passes;
      }
      if (draw_overlay(controls_, info)) changed();
    }
    ImGui::Render();
    window_->draw(o_.render.width, o_.render.height, controls_.overlay ? ImGui::GetDrawData() : nullptr);
    if (window_shot_) {
      rt2::write_image(*window_shot_, window_->read_back());
      if (!o_.quiet) std::printf("wrote %s\n", window_shot_->c_str());
      window_shot_.reset();
    }
    SDL_RenderPresent(window_->renderer());
  }

  void finish() {
    worker_.reset();
    if (!o_.interactive.frame_log.empty()) {
      rt2::io::write_output_file(o_.interactive.frame_log, log_.csv());
      if (!o_.quiet) std::printf("wrote %s\n", o_.interactive.frame_log.c_str());
    }
    if (!o_.quiet) std::printf("%s\n", log_.summary().c_str());
  }

  const Options& o_;
  std::optional<ScriptPlayer> script_;
  SDL_Keycode screenshot_key_;
  rt2::Camera start_camera_;
  bool animated_;   // the scene has an animation, which plays (space: pause, ',' '.': step)
  double duration_;  // its length: playing, it starts again from 0 after it; 0: still
  bool playing_;
  double seconds_;  // the animation's time, from --time
  FlyCamera fly_;
  ResolutionScaler scaler_;
  Controls controls_;
  std::optional<Window> window_;
  std::optional<RenderWorker> worker_;  // after the window: ends first
  Clock::time_point t0_;

  std::vector<bool> held_ = std::vector<bool>(SDL_NUM_SCANCODES, false);
  bool panel_drag_ = false;
  bool quit_ = false;
  // Frames to draw: 1 for a new image, 2 after input, since Dear ImGui shows some answers to
  // input (a combo box's list) a frame later.
  int redraw_ = 1;
  bool moving_ = false;
  double last_change_ = -1e9;
  std::uint64_t generation_ = 1;
  std::optional<Shown> shown_;
  double shown_at_ = 0.0, rate_ = 0.0;
  std::optional<RenderWorker::Failure> error_;  // the last one
  std::optional<std::string> window_shot_;
  FrameLog log_;
};

}  // namespace

bool available() { return true; }

void run_interactive(const Options& o) {
  // Everything that can be wrong with the input is found before a window opens.
  std::optional<ScriptPlayer> script;
  if (!o.interactive.script.empty())
    script.emplace(read_script(o.interactive.script), o.interactive.script);
  std::string key_name = o.interactive.screenshot_key;
  std::replace(key_name.begin(), key_name.end(), '_', ' ');
  const SDL_Keycode key = SDL_GetKeyFromName(key_name.c_str());
  if (key == SDLK_UNKNOWN)
    throw rt2::Error("--screenshot-key: unknown key '" + o.interactive.screenshot_key +
                     "' (SDL's key names, a blank written _: F12, P, PrintScreen, Left_Ctrl ...)");
  const char* x11 = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((!x11 || !*x11) && (!wayland || !*wayland))
    throw rt2::Error("--interactive needs a display, and neither DISPLAY nor WAYLAND_DISPLAY "
                     "is set (run it on a desktop, or under xvfb-run)");
  if (!o.output.empty()) rt2::check_writable_image(o.output);
  if (!o.interactive.frame_log.empty()) rt2::io::check_output_path(o.interactive.frame_log);
  rt2::check_image_fits(o.render.width, o.render.height);
  rt2::ScenePoser poser;
  rt2::Scene scene = load_scene(o, &poser);
  Viewer(o, std::move(scene), std::move(poser), std::move(script), key).run();
}

}  // namespace rt2cpr::viewer
