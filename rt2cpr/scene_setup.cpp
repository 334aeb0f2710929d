// rt2cpr/scene_setup.cpp — loading and compiling the scene of the options.
#include "rt2cpr/scene_setup.h"

#include "rt2/scene/builtin_scene.h"
#include "rt2/base/error.h"
#include "rt2/io/scene_io.h"
#include "rt2cpr/clock.h"

namespace rt2cpr {

rt2::Scene load_scene(const Options& o) {
  rt2::Scene scene = o.scene.empty() ? rt2::make_default_scene() : rt2::load_scene(o.scene);
  if (!o.camera.empty()) scene.camera = rt2::load_camera(o.camera);
  if (o.environment == "none")
    scene.environment.reset();
  else if (o.environment == "sky")
    scene.environment = rt2::EnvironmentDesc{};
  else if (!o.environment.empty())
    scene.environment = rt2::EnvironmentDesc{.image = o.environment};
  return scene;
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
                    rt2::Scene s = load_scene(o);
                    set_lights(s, o.lights, o.light_range);
                    return s;
                  })),
      compiled(timed(build_ms, [&] { return compile_at_camera(scene, o); })),
      renderer(compiled, rt2::View{scene.camera, o.render}),
      film(o.render.width, o.render.height) {}

}  // namespace rt2cpr
