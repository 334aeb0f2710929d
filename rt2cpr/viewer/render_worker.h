// rt2cpr/viewer/render_worker.h — the interactive viewer's renderer: a thread of its own
// that turns the newest view the window asks for into images, so that the window never
// waits for a frame.
//
// A moving view gets one quick frame per request: one sample per pixel, at the resolution
// divided by `scale`, from the scene compiled last. A still view gets the converged image
// pass by pass, each adding one sample per pixel to a film (rt2/image/film.h) and shown as
// it finishes; a new request drops the pass under way. The still is the same bits as
// `rt2cpr --camera ... --output` gives: the scene moved to the camera and compiled there
// (rt2cpr/scene_setup.h compile_at_camera), every pixel's samples added in the same order.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <stop_token>
#include <string>
#include <thread>
#include <vector>

#include "rt2/render/compiled_scene.h"
#include "rt2/image/film.h"
#include "rt2/image/image.h"
#include "rt2/io/scene_io.h"
#include "rt2/render/renderer.h"
#include "rt2/render/schedule.h"
#include "rt2cpr/options.h"

namespace rt2cpr::viewer {

// What the window wants to see.
struct ViewRequest {
  rt2::Camera camera;            // in the scene's own coordinates (as loaded)
  rt2::RenderSettings settings;  // the converged image's: size, samples, depth ...
  rt2::Schedule schedule;
  int lights = -1;               // total lights (rt2cpr/scene_setup.h set_lights); -1: the scene's
  double seconds = 0.0;          // an animated scene's time (Options::pose); else ignored
  bool moving = false;           // one quick frame instead of the converged image
  int scale = 1;                 // moving frames: width and height divided by this, >= 1
  // Changed by the window whenever anything above changes; a request with the generation
  // of the latest one changes nothing.
  std::uint64_t generation = 0;
};

// A finished image.
struct Shown {
  rt2::Image image;                 // linear, as a file render's
  std::vector<std::uint8_t> pixels;  // for the screen (rt2/image/display_pixels.h)
  bool moving = false;
  int pass = 0, passes = 1;         // the still: passes done, of passes
  double ms = 0.0;                  // rendering it (the last pass for a still)
  double idle_ms = 0.0;             // how long the worker waited for its request
  rt2::RayCounts rays;              // its rays (the last pass for a still)
  std::uint64_t generation = 0;     // of the request it answers
  bool converged() const { return !moving && pass == passes; }
};

class RenderWorker {
 public:
  // `scene`: the scene in its own coordinates with the options' camera and environment
  // (rt2cpr/scene_setup.h load_scene); its lights are set per request. `options`: the BVH, the
  // instruction set, the light range and the display mapping. Compiles the scene with
  // options.lights at its camera before the thread starts, so that a scene that cannot be
  // rendered throws rt2::Error here. A request at another time poses an animated scene
  // again: posed at that time by `poser` (load_scene's; empty: the worker loads the file
  // once more for one), placed (CompiledScene::place) for a moving frame, compiled for a
  // still. `shown` is called from the worker's thread after every finished image (to wake
  // the window).
  RenderWorker(rt2::Scene scene, const Options& options, std::function<void()> shown,
               rt2::ScenePoser poser = {});
  ~RenderWorker();  // drops the pass under way and joins the thread
  RenderWorker(const RenderWorker&) = delete;
  RenderWorker& operator=(const RenderWorker&) = delete;

  // The newest request wins; a still's pass for an older generation is dropped.
  void request(const ViewRequest& r);
  // The newest image finished since the last call, moved into `out`; false if none.
  bool take(Shown& out);
  // What went wrong with the last request that failed (a light count the memory does not
  // hold ...) and that request's generation, cleared by the call; nothing when nothing did.
  // The previous scene stays.
  struct Failure {
    std::string message;
    std::uint64_t generation = 0;
  };
  std::optional<Failure> take_error();

 private:
  void run(std::stop_token quit);
  void compile_for(const ViewRequest& r, bool at_camera);
  void publish(const rt2::Film& film, Shown&& s);

  rt2::Scene base_;  // the options' scene, posed at posed_seconds_ (owned by the worker thread)
  double posed_seconds_;
  rt2::ScenePoser poser_;  // of base_'s file, when it moves
  const Options options_;
  const std::function<void()> shown_cb_;

  // Owned by the worker thread.
  std::unique_ptr<rt2::CompiledScene> compiled_;
  rt2::vec4 centre_;   // where compiled_'s origin is in the scene's coordinates
  int compiled_lights_ = -2;
  rt2::Film moving_film_, still_film_;
  std::uint64_t still_generation_ = 0;
  int still_pass_ = 0;
  bool still_started_ = false;

  std::mutex mutex_;  // guards what follows
  std::condition_variable_any wake_;
  ViewRequest latest_;
  bool have_request_ = false;
  std::uint64_t done_generation_ = 0;
  bool done_any_ = false;
  std::stop_source pass_stop_;
  bool pass_is_still_ = false;
  std::optional<Shown> shown_;
  std::optional<Failure> error_;

  std::jthread thread_;  // started last, by the constructor's body
};

}  // namespace rt2cpr::viewer
