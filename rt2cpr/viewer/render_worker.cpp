// rt2cpr/viewer/render_worker.cpp — the worker thread's loop.
#include "rt2cpr/viewer/render_worker.h"

#include <algorithm>
#include <chrono>
#include <new>
#include <utility>

#include "rt2/image/display_pixels.h"
#include "rt2/base/error.h"
#include "rt2/io/text.h"
#include "rt2cpr/scene_setup.h"

namespace rt2cpr::viewer {

namespace {

bool same_point(const rt2::vec4& a, const rt2::vec4& b) {
  return a.x() == b.x() && a.y() == b.y() && a.z() == b.z();
}

}  // namespace

RenderWorker::RenderWorker(rt2::Scene scene, const Options& options, std::function<void()> shown,
                           rt2::ScenePoser poser)
    : base_(std::move(scene)),
      posed_seconds_(options.pose.seconds),
      poser_(std::move(poser)),
      options_(options),
      shown_cb_(std::move(shown)) {
  if (base_.animation >= 0 && !poser_) {
    const rt2::io::WarningsOff quiet;  // the scene's own load warned
    load_scene(options_, &poser_);
  }
  ViewRequest first;
  first.camera = base_.camera;
  first.seconds = options.pose.seconds;
  first.lights = options.lights;
  compile_for(first, true);
  thread_ = std::jthread([this](std::stop_token quit) { run(quit); });
}

RenderWorker::~RenderWorker() {
  thread_.request_stop();  // and through run's stop_callback, the pass under way
  thread_.join();
}

void RenderWorker::request(const ViewRequest& r) {
  const std::lock_guard lock(mutex_);
  if (have_request_ && r.generation == latest_.generation) return;
  if (pass_is_still_) pass_stop_.request_stop();  // a moving frame is always finished
  latest_ = r;
  have_request_ = true;
  wake_.notify_all();
}

bool RenderWorker::take(Shown& out) {
  const std::lock_guard lock(mutex_);
  if (!shown_) return false;
  out = std::move(*shown_);
  shown_.reset();
  return true;
}

std::optional<RenderWorker::Failure> RenderWorker::take_error() {
  const std::lock_guard lock(mutex_);
  return std::exchange(error_, std::nullopt);
}

// The scene at the request's time with its lights, compiled where the request's camera is
// (a still), or wherever it was last compiled (a moving frame after a change of lights or
// time; a change of time alone places the posed scene in the compiled one).
void RenderWorker::compile_for(const ViewRequest& r, bool at_camera) {
  const bool time_changed = base_.animation >= 0 && r.seconds != posed_seconds_;
  std::optional<rt2::Scene> posed;  // the scene at the request's time, once it is placed
  if (time_changed) posed = load_scene_at(options_, poser_, r.seconds);
  const bool lights_changed = r.lights != compiled_lights_;
  if (compiled_ && !lights_changed && !time_changed &&
      (!at_camera || same_point(centre_, r.camera.position())))
    return;
  rt2::Scene scene = posed ? *posed : base_;
  set_lights(scene, r.lights, options_.light_range);
  scene.camera = r.camera;
  if (!at_camera && compiled_) {  // keep the current origin: only the lights changed
    scene.camera.translate(centre_ - r.camera.position());
  }
  const rt2::vec4 centre = scene.camera.position();
  try {
    if (compiled_ && !at_camera && !lights_changed) {
      rt2::recenter_on_camera(scene);  // place validates it
      compiled_->place(scene, options_.bvh, options_.isa, rt2::same_topology(base_, scene));
    } else {
      compiled_ = std::make_unique<rt2::CompiledScene>(compile_at_camera(scene, options_));
    }
  } catch (...) {
    compiled_.reset();  // perhaps half placed: the next request compiles afresh
    throw;
  }
  if (posed) {
    base_ = std::move(*posed);
    posed_seconds_ = r.seconds;
  }
  centre_ = centre;
  compiled_lights_ = r.lights;
}

void RenderWorker::publish(const rt2::Film& film, Shown&& s) {
  film.resolve(s.image);
  rt2::to_display_pixels(s.image, options_.display, s.pixels);
  {
    const std::lock_guard lock(mutex_);
    shown_ = std::move(s);
  }
  if (shown_cb_) shown_cb_();
}

void RenderWorker::run(std::stop_token quit) {
  // Quitting drops whatever pass is under way, a moving frame's too.
  const std::stop_callback on_quit(quit, [this] {
    const std::lock_guard lock(mutex_);
    pass_stop_.request_stop();
  });
  auto idle_since = std::chrono::steady_clock::now();
  for (;;) {
    ViewRequest r;
    std::stop_token stop;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, quit, [&] {
        return have_request_ && (!done_any_ || latest_.generation != done_generation_);
      });
      if (quit.stop_requested()) return;
      r = latest_;
      pass_stop_ = std::stop_source();
      stop = pass_stop_.get_token();
      pass_is_still_ = !r.moving;
    }
    const double idle_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - idle_since).count();
    bool done = true;
    try {
      compile_for(r, !r.moving);
      rt2::Camera camera = r.camera;
      camera.translate(-centre_);
      Shown s;
      s.moving = r.moving;
      s.generation = r.generation;
      s.idle_ms = idle_ms;
      if (r.moving) {
        rt2::RenderSettings st = r.settings;
        st.width = std::max(1, st.width / r.scale);
        st.height = std::max(1, st.height / r.scale);
        st.subpixels = 1;
        st.passes = 1;
        if (moving_film_.width() != st.width || moving_film_.height() != st.height)
          moving_film_ = rt2::Film(st.width, st.height);
        else
          moving_film_.clear();
        const rt2::Renderer renderer(*compiled_, rt2::View{camera, st});
        const rt2::FrameResult f = rt2::render_pass(renderer, r.schedule, moving_film_, 0, {}, stop);
        if (f.complete) {  // else quitting
          s.ms = f.ms;
          s.rays = f.rays;
          publish(moving_film_, std::move(s));
        }
      } else {
        rt2::RenderSettings st = r.settings;
        st.passes = st.subpixels;  // one sample per pixel per pass
        if (!still_started_ || still_generation_ != r.generation) {
          still_started_ = true;
          still_generation_ = r.generation;
          still_pass_ = 0;
          if (still_film_.width() != st.width || still_film_.height() != st.height)
            still_film_ = rt2::Film(st.width, st.height);
          else
            still_film_.clear();
        }
        const rt2::Renderer renderer(*compiled_, rt2::View{camera, st});
        const rt2::FrameResult f =
            rt2::render_pass(renderer, r.schedule, still_film_, still_pass_, {}, stop);
        if (!f.complete) {
          still_started_ = false;  // the film holds part of a pass: start again when asked
          done = false;
        } else {
          ++still_pass_;
          done = still_pass_ == st.passes;
          s.pass = still_pass_;
          s.passes = st.passes;
          s.ms = f.ms;
          s.rays = f.rays;
          publish(still_film_, std::move(s));
        }
      }
    } catch (const std::bad_alloc&) {
      const std::lock_guard lock(mutex_);
      error_ = Failure{"out of memory", r.generation};
    } catch (const std::exception& e) {  // rt2::Error, or anything a library throws
      const std::lock_guard lock(mutex_);
      error_ = Failure{e.what(), r.generation};
    }
    idle_since = std::chrono::steady_clock::now();
    const std::lock_guard lock(mutex_);
    pass_is_still_ = false;
    if (done) {
      done_generation_ = r.generation;
      done_any_ = true;
    }
  }
}

}  // namespace rt2cpr::viewer
