// The viewer's render worker (rt2cpr/viewer/render_worker.h) against the file render, its
// oracle: whatever requests came before, however fast and mid-pass, the converged still of
// a view is the same bits as rendering that view as `rt2cpr --camera ... --output` does
// (rt2cpr/scene_setup.h: load, set the lights, move to the camera, compile, render every pass).
#include "rt2cpr/viewer/render_worker.h"

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <cstring>
#include <mutex>

#include "rt2/base/error.h"
#include "rt2cpr/scene_setup.h"
#include "rt2cpr/viewer/fly_camera.h"
#include "tests/rt2/io/animated_gltf.h"
#include "tests/rt2/temp_dir.h"

namespace rt2cpr::viewer {
namespace {

Options small_options() {
  Options o;  // the built-in scene
  o.render.width = 40;
  o.render.height = 30;
  o.render.subpixels = 4;
  o.render.depth = 4;
  o.schedule.threads = 2;
  o.schedule.tile = 8;
  return o;
}

// What `rt2cpr --camera <camera> --lights <lights>` renders with `settings`.
rt2::Image file_render(const Options& o, const rt2::Camera& camera, int lights,
                       const rt2::RenderSettings& settings) {
  rt2::Scene scene = load_scene(o);
  scene.camera = camera;
  set_lights(scene, lights, o.light_range);
  const rt2::CompiledScene compiled = compile_at_camera(scene, o);
  rt2::Image image;
  rt2::render_frame(rt2::Renderer(compiled, rt2::View{scene.camera, settings}), o.schedule, image);
  return image;
}

bool identical(const rt2::Image& a, const rt2::Image& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)) == 0;
}

// A worker with a way to wait for its images.
class Worker {
 public:
  explicit Worker(const Options& o)
      : worker_(load_scene(o), o, [this] {
          const std::lock_guard lock(m_);
          ++shown_;
          cv_.notify_all();
        }) {}
  RenderWorker& operator*() { return worker_; }
  RenderWorker* operator->() { return &worker_; }
  // The next image that satisfies `want` (a generous guard against a hang, not a timing).
  template <class Want>
  Shown wait_for(Want&& want) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::minutes(5);
    for (;;) {
      Shown s;
      if (worker_.take(s) && want(s)) return s;
      std::unique_lock lock(m_);
      const int seen = shown_;
      cv_.wait_for(lock, std::chrono::milliseconds(50), [&] { return shown_ != seen; });
      if (std::chrono::steady_clock::now() > until) {
        ADD_FAILURE() << "no such image came";
        return {};
      }
    }
  }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  int shown_ = 0;
  RenderWorker worker_;  // last: its thread calls back into the members above
};

ViewRequest request(const Options& o, const rt2::Camera& camera, bool moving, std::uint64_t generation) {
  ViewRequest r;
  r.camera = camera;
  r.settings = o.render;
  r.schedule = o.schedule;
  r.lights = o.lights;
  r.moving = moving;
  r.generation = generation;
  return r;
}

TEST(RenderWorker, TheConvergedStillIsTheFileRenderOfItsCamera) {
  const Options o = small_options();
  Worker w(o);
  FlyCamera fly(load_scene(o).camera, 1.0f);
  std::uint64_t g = 1;
  w->request(request(o, fly.camera(), false, g));
  const Shown first = w.wait_for([&](const Shown& s) { return s.converged() && s.generation == g; });
  EXPECT_EQ(first.passes, 4);
  EXPECT_TRUE(identical(first.image, file_render(o, fly.camera(), -1, o.render)));

  // Moved away (a moving frame, the scene still compiled where it was), then still again.
  fly.move(1.0f, 0.3f, 0.1f, 0.7f);
  fly.turn(40.0f, -10.0f);
  w->request(request(o, fly.camera(), true, ++g));
  const Shown moving = w.wait_for([&](const Shown& s) { return s.moving && s.generation == g; });
  EXPECT_EQ(moving.image.width, 40);
  EXPECT_EQ(moving.rays.primary, 40u * 30u);  // one sample per pixel
  w->request(request(o, fly.camera(), false, ++g));
  const Shown still = w.wait_for([&](const Shown& s) { return s.converged() && s.generation == g; });
  EXPECT_TRUE(identical(still.image, file_render(o, fly.camera(), -1, o.render)));
  EXPECT_FALSE(identical(still.image, first.image));
}

// Many requests, moving and still, each replacing the last while a pass renders: none is
// waited for, passes are dropped mid-way, and the last one still converges to its file render.
TEST(RenderWorker, RequestsThatReplaceEachOtherMidPassEndInTheLastOnesFileRender) {
  Options o = small_options();
  o.render.subpixels = 16;
  Worker w(o);
  FlyCamera fly(load_scene(o).camera, 1.0f);
  std::uint64_t g = 0;
  for (int i = 0; i < 60; ++i) {
    fly.turn(7.0f, 1.0f);
    fly.move(0.2f, 0.0f, 0.0f, 0.1f);
    ViewRequest r = request(o, fly.camera(), i % 3 == 0, ++g);
    r.scale = 1 + i % 4;
    r.schedule.backend = rt2::Backend(i % 3);
    w->request(r);
    if (i % 7 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(3));
  }
  w->request(request(o, fly.camera(), false, ++g));
  const Shown s = w.wait_for([&](const Shown& x) { return x.converged() && x.generation == g; });
  EXPECT_TRUE(identical(s.image, file_render(o, fly.camera(), -1, o.render)));
}

// An animated scene played (moving frames at advancing times), then still: the still is the
// file render at its time (`rt2cpr --time`), and differs from the one at the start.
TEST(RenderWorker, AnAnimatedSceneStillIsTheFileRenderAtItsTime) {
  const rt2::test::TempDir dir("worker");
  Options o = small_options();
  o.scene = dir.write("a.gltf", rt2::test::animated_gltf());
  o.pose.seconds = 0.25;
  Worker w(o);
  const rt2::Camera camera = load_scene(o).camera;
  std::uint64_t g = 0;
  for (const double t : {0.3, 0.45, 0.7}) {
    ViewRequest r = request(o, camera, true, ++g);
    r.seconds = t;
    w->request(r);
    w.wait_for([&](const Shown& s) { return s.moving && s.generation == g; });
  }
  ViewRequest r = request(o, camera, false, ++g);
  r.seconds = 0.9;
  w->request(r);
  const Shown s = w.wait_for([&](const Shown& x) { return x.converged() && x.generation == g; });
  Options at = o;
  at.pose.seconds = 0.9;
  EXPECT_TRUE(identical(s.image, file_render(at, camera, -1, o.render)));
  EXPECT_FALSE(identical(s.image, file_render(o, camera, -1, o.render)));
}

// Settings and lights changed between requests: the still is the file render with them.
TEST(RenderWorker, ChangedSettingsAndLightsConvergeToTheirFileRender) {
  const Options o = small_options();
  Worker w(o);
  const rt2::Camera camera = load_scene(o).camera;
  ViewRequest r = request(o, camera, false, 1);
  w->request(r);
  w.wait_for([](const Shown& s) { return s.converged(); });
  r.settings.depth = 9;
  r.settings.subpixels = 3;
  r.settings.pattern = rt2::Pattern::circle;
  r.settings.watertight = true;
  r.settings.min_weight = 0.05f;
  r.lights = 3;
  r.generation = 2;
  w->request(r);
  const Shown s = w.wait_for([](const Shown& x) { return x.converged() && x.generation == 2; });
  EXPECT_EQ(s.passes, 3);
  EXPECT_TRUE(identical(s.image, file_render(o, camera, 3, r.settings)));
}

TEST(RenderWorker, AMovingFrameIsOneSamplePerPixelAtTheScaledSize) {
  const Options o = small_options();
  Worker w(o);
  ViewRequest r = request(o, load_scene(o).camera, true, 1);
  r.scale = 3;
  w->request(r);
  const Shown s = w.wait_for([](const Shown& x) { return x.moving; });
  EXPECT_EQ(s.image.width, 13);
  EXPECT_EQ(s.image.height, 10);
  EXPECT_EQ(s.pixels.size(), std::size_t(13 * 10 * 4));
  EXPECT_EQ(s.rays.primary, 130u);
  EXPECT_FALSE(s.converged());
}

// A request whose lights cannot be set is reported, and the worker goes on with the next.
TEST(RenderWorker, AFailedRequestIsReportedAndTheNextOneRenders) {
  Options o = small_options();
  o.lights = 4;
  o.light_range = rt2::RangeInterval{1.0f, 2.0f};
  Worker w(o);
  ViewRequest r = request(o, load_scene(o).camera, false, 1);
  r.lights = -1;  // the scene's own: nothing takes --light-range
  w->request(r);
  std::optional<RenderWorker::Failure> error;
  for (int i = 0; i < 5000 && !error; ++i) {
    error = w->take_error();
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ASSERT_TRUE(error);
  EXPECT_NE(error->message.find("--light-range"), std::string::npos) << error->message;
  EXPECT_EQ(error->generation, 1u);
  r.lights = 4;
  r.generation = 2;
  w->request(r);
  const Shown s = w.wait_for([](const Shown& x) { return x.converged() && x.generation == 2; });
  EXPECT_TRUE(identical(s.image, file_render(o, r.camera, 4, o.render)));
}

TEST(RenderWorker, ASceneThatCannotBeRenderedThrowsBeforeAnyThread) {
  Options o = small_options();
  o.environment = "/nonexistent/sky.exr";
  rt2::Scene scene = load_scene(o);  // loads: the image is opened when the scene compiles
  EXPECT_THROW(RenderWorker(std::move(scene), o, {}), rt2::Error);
}

// Destroyed while a long pass renders, the worker drops it between tiles: the pass after
// the first one shown is never finished, let alone shown. (A worker that finished its pass
// before ending would show a second one: each pass here takes far longer than the test's
// thread needs to wake and destroy it.)
TEST(RenderWorker, DestroyedMidPassDropsThePassUnderWay) {
  Options o = small_options();
  o.render.width = 640;
  o.render.height = 480;
  o.render.depth = 16;
  o.render.subpixels = 1024;
  o.schedule = rt2::Schedule{rt2::Backend::serial, 1, 1, 16};
  int shown = 0;
  std::mutex m;
  std::condition_variable cv;
  {
    RenderWorker w(load_scene(o), o, [&] {
      const std::lock_guard lock(m);
      ++shown;
      cv.notify_all();
    });
    w.request(request(o, load_scene(o).camera, false, 1));
    std::unique_lock lock(m);
    cv.wait(lock, [&] { return shown >= 1; });
  }
  EXPECT_EQ(shown, 1);
}

}  // namespace
}  // namespace rt2cpr::viewer
