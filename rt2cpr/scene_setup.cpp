// rt2cpr/scene_setup.cpp — loading and compiling the scene of the options.
#include "rt2cpr/scene_setup.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include "rt2/scene/builtin_scene.h"
#include "rt2/base/error.h"
#include "rt2/io/scene_io.h"
#include "rt2/io/text.h"
#include "rt2cpr/clock.h"

namespace rt2cpr {

namespace {

// What load_scene does to the scene a file gives.
void as_the_options_say(rt2::Scene& scene, const Options& o) {
  if (!o.camera.empty()) {
    scene.camera = rt2::load_camera(o.camera);
    scene.framed_bounds.reset();
  }
  rt2::fit_framed_camera(scene, o.render.width, o.render.height);
  if (o.environment == "none") {
    scene.environment.reset();
  } else if (o.environment == "sky") {  // the scene's sun, intensity and rotation stay
    rt2::EnvironmentDesc sky = scene.environment.value_or(rt2::EnvironmentDesc{});
    sky.image.clear();
    scene.environment = sky;
  } else if (!o.environment.empty()) {
    scene.environment = rt2::EnvironmentDesc{.image = o.environment};
  }
  warn_about_added_lights(scene, o.lights, o.light_range);
}

}  // namespace

rt2::Scene load_scene(const Options& o, rt2::ScenePoser* poser) {
  if (o.scene.empty() && !o.pose.animation.empty())
    throw rt2::Error("the built-in scene has no animations (--animation " + o.pose.animation + ")");
  if (poser) *poser = rt2::ScenePoser();
  rt2::Scene scene = o.scene.empty() ? rt2::make_default_scene()
                                     : rt2::load_scene(o.scene, o.assets, o.pose, poser);
  as_the_options_say(scene, o);
  return scene;
}

rt2::Scene load_scene_at(const Options& o, const rt2::ScenePoser& poser, double seconds) {
  rt2::Scene scene = poser.at(seconds);
  const rt2::io::WarningsOff quiet;  // the first load warned
  as_the_options_say(scene, o);
  return scene;
}

void warn_about_added_lights(const rt2::Scene& scene, int lights,
                             const std::optional<rt2::RangeInterval>& range) {
  if (lights < 0 || std::size_t(lights) <= scene.lights.size() || scene.light_field || range)
    return;
  // set_light_count's ring: white lights of the first light's intensity (1 without lights).
  const float each = scene.lights.empty() ? 1.0f : scene.lights.front().intensity;
  const std::size_t added = std::size_t(lights) - scene.lights.size();
  float own = 0.0f;
  for (const rt2::Light& l : scene.lights)
    own += l.intensity * std::max({l.color[0], l.color[1], l.color[2]});
  const double reference = own > 0.0f ? own : 1.0;
  const double brighter = (reference + double(each) * double(added)) / reference;
  if (!(brighter > kMaxAddedBrightening)) return;
  char times[32];
  std::snprintf(times, sizeof times, "%.3g", brighter);
  rt2::io::warn("--lights " + std::to_string(lights) + " adds " + std::to_string(added) +
                " lights without a range, " + times + " times the light of the scene's own" +
                (scene.lights.empty() ? " (one light of intensity 1 for a scene without any)"
                                      : "") +
                ": what they light turns white; --light-range gives them a range");
}

void set_lights(rt2::Scene& scene, int lights, const std::optional<rt2::RangeInterval>& range) {
  if (range && !scene.light_field && (lights < 0 || std::size_t(lights) <= scene.lights.size()))
    throw rt2::Error("--light-range applies to the lights --lights adds and to a scene's "
                     "[light_field]; this scene has no light field and no lights are added");
  if (lights >= 0 || range)
    rt2::set_light_count(scene, lights >= 0 ? std::size_t(lights) : scene.lights.size(), range);
}

rt2::CompiledScene compile_at_camera(rt2::Scene& scene, const Options& o) {
  scene.validate();
  rt2::recenter_on_camera(scene);
  return rt2::CompiledScene::compile(scene, o.bvh, o.isa);
}

namespace {

// make(), with the milliseconds it took into `ms`.
template <class Make>
auto timed(double& ms, Make make) {
  const auto t0 = Clock::now();
  auto made = make();
  ms = ms_since(t0);
  return made;
}

}  // namespace

RenderSetup::RenderSetup(const Options& o)
    : scene(timed(load_ms,
                  [&] {
                    rt2::Scene s = load_scene(o, &poser);
                    set_lights(s, o.lights, o.light_range);
                    return s;
                  })),
      compiled(timed(build_ms, [&] { return compile_at_camera(scene, o); })),
      renderer(compiled, rt2::View{scene.camera, o.render}),
      film(o.render.width, o.render.height) {}

std::optional<RenderSetup::PoseTimes> RenderSetup::pose(const Options& o, int frame) {
  if (!poser) return std::nullopt;
  PoseTimes t;
  const rt2::io::WarningsOff quiet;  // the first load warned
  rt2::Scene next = timed(t.load_ms, [&] {
    rt2::Scene s = load_scene_at(o, poser, frame_seconds(o, frame));
    set_lights(s, o.lights, o.light_range);
    return s;
  });
  const auto t0 = Clock::now();
  rt2::recenter_on_camera(next);  // place validates it
  compiled.place(next, o.bvh, o.isa, rt2::same_topology(scene, next));
  scene = std::move(next);
  t.placed = compiled.placed;
  renderer.set_camera(scene.camera);
  t.place_ms = ms_since(t0);
  return t;
}

}  // namespace rt2cpr
