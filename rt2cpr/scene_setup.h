// rt2cpr/scene_setup.h — the scene the command line describes, shared by file renders and
// the interactive viewer: loaded, with its camera, environment and lights as the options
// say, and made ready to render from its camera.
#pragma once

#include <optional>

#include "rt2/render/compiled_scene.h"
#include "rt2/image/film.h"
#include "rt2/io/scene_io.h"
#include "rt2/render/renderer.h"
#include "rt2/scene/scene.h"
#include "rt2cpr/options.h"

namespace rt2cpr {

// The scene of `o.scene` (the built-in one when empty) under o.assets, in its own
// coordinates, with the camera of --camera when given, else a framed camera
// (Scene::framed_bounds: a bare OBJ, a glTF without a camera) fitted to o.render's width and
// height, and the environment of --environment when given (`sky` keeps the scene's sun,
// intensity and rotation); its lights are the file's (set_lights sets them), with
// warn_about_added_lights's warning. For a scene that moves, `poser` (when given) keeps its
// parsed file. Throws rt2::Error.
rt2::Scene load_scene(const Options& o, rt2::ScenePoser* poser = nullptr);

// load_scene(o) with o.pose.seconds = `seconds`, bit for bit, from the poser load_scene gave
// (the file is not read again), without warnings. Throws rt2::Error.
rt2::Scene load_scene_at(const Options& o, const rt2::ScenePoser& poser, double seconds);

// How much brighter than its own lights (their summed intensity times colour) the lights
// --lights adds may make a scene before warn_about_added_lights warns: two stops, so that
// whatever the scene's own lights show at a quarter of white or more turns white.
inline constexpr double kMaxAddedBrightening = 4.0;

// One `warning:` line on stderr when `lights` (the total of --lights; < 0: none added) adds
// ring lights without a range (a scene without a light field, no --light-range) that make
// the scene more than kMaxAddedBrightening times as bright as its own lights (or one light
// of intensity 1 when it has none): what happens, and that --light-range is the fix.
void warn_about_added_lights(const rt2::Scene& scene, int lights,
                             const std::optional<rt2::RangeInterval>& range);

// The total light count `lights` (< 0: the scene's own) with --light-range's ranges
// (rt2/scene/scene.h set_light_count). Throws rt2::Error when a range is given but nothing
// takes it.
void set_lights(rt2::Scene& scene, int lights, const std::optional<rt2::RangeInterval>& range);

// The time frame `frame` (0, 1, ...) of `o` shows: --time plus frame / --fps seconds.
inline double frame_seconds(const Options& o, int frame) { return o.pose.seconds + frame / o.fps; }

// `scene` validated, moved so that its camera is at the origin (full float precision where
// the pixels come from: Scene::origin keeps where the world's origin went) and compiled.
rt2::CompiledScene compile_at_camera(rt2::Scene& scene, const Options& o);

// What a file render has before its first frame: the scene loaded with its lights and
// compiled (with how long each step took), the renderer of its view and an empty film.
// Not movable: the renderer refers to the compiled scene.
struct RenderSetup {
  // Throws rt2::Error (or std::bad_alloc); call rt2::check_image_fits first.
  explicit RenderSetup(const Options& o);
  RenderSetup(const RenderSetup&) = delete;
  RenderSetup& operator=(const RenderSetup&) = delete;

  // An animated scene (Scene::animation >= 0) posed for frame `frame` of `o`: posed again
  // at frame_seconds(o, frame) (load_scene_at), placed (CompiledScene::place: trees, lights; the materials,
  // textures and environment stay) and its camera given to the renderer, so that the frame
  // is what a fresh set-up at that time renders. Returns how long loading and placing took;
  // nothing, doing nothing, for a scene that does not move. Throws rt2::Error.
  struct PoseTimes {
    double load_ms = 0.0, place_ms = 0.0;
    rt2::CompiledScene::Placed placed = rt2::CompiledScene::Placed::built;
  };
  std::optional<PoseTimes> pose(const Options& o, int frame);

  double load_ms = 0.0;   // load_scene and set_lights
  double build_ms = 0.0;  // compile_at_camera
  rt2::ScenePoser poser;  // the parsed file of a scene that moves
  rt2::Scene scene;
  rt2::CompiledScene compiled;
  rt2::Renderer renderer;
  rt2::Film film;
};

}  // namespace rt2cpr
