// rt2cpr/options.cpp — CLI11 definitions, presets (SPEC "presets") and validation.
#include "rt2cpr/options.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <climits>
#include <filesystem>
#include <cmath>
#include <initializer_list>
#include <iostream>
#include <map>

#include "rt2/base/error.h"
#include "rt2/image/output_file.h"
#include "rt2/base/version.h"

namespace rt2cpr {

namespace {

struct Preset {
  int width, height, subpixels, depth, lights;
};

// The thesis's presets (table in thesis 5.4).
const std::map<std::string, Preset> kPresets = {
    {"low", {512, 512, 1, 1, 1}},
    {"middle", {800, 600, 2, 2, 1}},
    {"hard", {1024, 768, 3, 4, 2}},
    {"veryhard", {1920, 1080, 3, 8, 2}},
};

const char* kExamples = R"(Examples:
  rt2cpr --output out/default.png                      render the built-in scene
  rt2cpr --preset hard --frames 10 --backend tbb       benchmark a thesis preset
  rt2cpr --scene scenes/glass.toml --subpixels 9 --pattern circle --output glass.exr
  rt2cpr --scene bunny.obj --output bunny.png          an OBJ alone is framed automatically
  rt2cpr --preset low --leaf-size 64 --split midpoint --stats run.json
  rt2cpr --preset middle --lights 8 --depth 16 --min-weight 0 --threads 2 --grain 8

Presets (explicit options override them):
  low       512x512    subpixels 1  depth 1  lights 1
  middle    800x600    subpixels 2  depth 2  lights 1
  hard      1024x768   subpixels 3  depth 4  lights 2
  veryhard  1920x1080  subpixels 3  depth 8  lights 2
Without a preset: 800x600, subpixels 1, depth 4, the scene's own lights.
Extra lights (--lights beyond the scene's own) are white, on a ring above the scene.)";

using Named = std::pair<const char*, const std::string*>;  // an option and its file

// An output file (`flag` `path`) that names one of `others` is refused: writing it would
// overwrite an input or another output.
void refuse_same_file(const char* flag, const std::string& path, std::initializer_list<Named> others) {
  for (const auto& [other_flag, other] : others)
    if (!other->empty() && rt2::io::same_file(path, *other))
      throw rt2::Error(std::string(flag) + " " + path + " is the same file as " + other_flag + " " +
                       *other);
}

// The files named on the command line: none empty, and the statistics and the image never
// overwrite an input or each other.
template <class Given>
void check_paths(const Options& o, Given&& given) {
  for (const auto& [flag, value] : {std::pair{"--scene", &o.scene}, {"--output", &o.output},
                                    {"--stats", &o.stats}, {"--reference", &o.reference},
                                    {"--camera", &o.camera}})
    if (given(flag) && value->empty()) throw rt2::Error(std::string(flag) + ": empty file name");
  if (!o.stats.empty()) {
    if (std::filesystem::path(o.stats).extension() != ".json")
      throw rt2::Error("--stats " + o.stats + ": the statistics file must end in .json");
    refuse_same_file("--stats", o.stats,
                     {{"--scene", &o.scene}, {"--output", &o.output}, {"--reference", &o.reference},
                      {"--camera", &o.camera}, {"--environment", &o.environment}});
  }
  if (!o.output.empty())
    refuse_same_file("--output", o.output,
                     {{"--scene", &o.scene}, {"--reference", &o.reference}, {"--camera", &o.camera},
                      {"--environment", &o.environment}});
}

// The viewer's options only with --interactive, and the file render's only without.
template <class Given>
void check_interactive(const Options& o, Given&& given) {
  const Interactive& v = o.interactive;
  if (!v.on) {
    for (const char* flag : {"--script", "--screenshot-key", "--target-fps", "--frame-log"})
      if (given(flag)) throw rt2::Error(std::string(flag) + " needs --interactive");
    return;
  }
  for (const char* flag : {"--frames", "--stats", "--reference", "--time-budget",
                           "--animate-lights", "--passes"})
    if (given(flag)) throw rt2::Error(std::string(flag) + " does not apply to --interactive");
  for (const auto& [flag, value] : {std::pair{"--script", &v.script}, {"--frame-log", &v.frame_log},
                                    {"--screenshot-key", &v.screenshot_key}})
    if (given(flag) && value->empty()) throw rt2::Error(std::string(flag) + ": empty value");
  if (!(v.target_fps >= 0.0 && v.target_fps <= 1000.0))
    throw rt2::Error("target-fps must be in [0, 1000] (0 = never lower the resolution), got " +
                     std::to_string(v.target_fps));
  if (!v.frame_log.empty()) {
    if (std::filesystem::path(v.frame_log).extension() != ".csv")
      throw rt2::Error("--frame-log " + v.frame_log + ": the frame log must end in .csv");
    refuse_same_file("--frame-log", v.frame_log,
                     {{"--scene", &o.scene}, {"--output", &o.output}, {"--script", &v.script},
                      {"--camera", &o.camera}, {"--environment", &o.environment}});
  }
}

// --light-range: "R" or "LO,HI", each in (0, 1e15], LO <= HI.
rt2::RangeInterval parse_range_interval(const std::string& text) {
  const auto fail = [&]() -> rt2::RangeInterval {
    throw rt2::Error("light-range must be R or LO,HI with 0 < LO <= HI <= 1e15, got '" + text +
                     "'");
  };
  const auto number = [&](const std::string& t) {
    std::size_t used = 0;
    float v = 0.0f;
    try {
      v = std::stof(t, &used);
    } catch (const std::exception&) {
      fail();
    }
    if (used != t.size() || !(v > 0.0f && v <= 1e15f)) fail();
    return v;
  };
  const std::size_t comma = text.find(',');
  rt2::RangeInterval r;
  r.lo = number(text.substr(0, comma));
  r.hi = comma == std::string::npos ? r.lo : number(text.substr(comma + 1));
  if (!(r.lo <= r.hi)) fail();
  return r;
}

void apply_preset(const std::string& name, Options& o) {
  const Preset& p = kPresets.at(name);
  o.render.width = p.width;
  o.render.height = p.height;
  o.render.subpixels = p.subpixels;
  o.render.depth = p.depth;
  o.lights = p.lights;
}

}  // namespace

std::optional<Options> parse_options(int argc, char** argv) {
  CLI::App app{"rt2cpr — render a scene with rt2, a CPU Whitted ray tracer", "rt2cpr"};
  app.footer(kExamples);
  app.get_formatter()->column_width(34);
  app.option_defaults()->always_capture_default();

  Options o;  // defaults without a preset: 800x600, 1 subpixel, depth 4, the scene's lights
  o.render.width = 800;
  o.render.height = 600;
  o.render.depth = 4;
  int width = o.render.width, height = o.render.height, subpixels = o.render.subpixels,
      depth = o.render.depth, lights = -1, threads = o.schedule.threads, grain = o.schedule.grain,
      passes = o.render.passes, tile = o.schedule.tile, block = o.render.block;
  long long leaf = o.bvh.max_leaf_size;
  float min_weight = o.render.min_weight;
  std::string pattern = "grid", split = "sah", backend = "omp", triangle_test = "fast",
              isa = rt2::isa_name(o.isa), packets = "on", shading_lanes = "on", positional_scene,
              light_culling = "clustered", light_lists = "bvh", shadows = "on",
              tone_curve = "none";
  int light_slices = o.render.light_slices;
  std::string light_range;
  bool version = false;

  app.add_option("scene_file", positional_scene, "the scene, as with --scene")
      ->default_str("");
  app.add_option("--scene", o.scene, "scene file (.toml), mesh (.obj) or glTF 2.0 (.gltf/.glb)")
      ->default_str("built-in scene");
  app.add_option("--camera", o.camera, "the camera of a TOML file holding a [camera] table "
                                      "(what the viewer's C key prints)")
      ->default_str("the scene's");
  app.add_option("--preset", o.preset, "low | middle | hard | veryhard")->default_str("none");
  app.add_option("--width", width, "image width in pixels");
  app.add_option("--height", height, "image height in pixels");
  app.add_option("--subpixels", subpixels, "samples per pixel (>= 1)");
  app.add_option("--pattern", pattern, "subpixel pattern: grid | circle");
  app.add_option("--depth", depth, "recursion depth (0 = no reflection/refraction rays)");
  app.add_option("--min-weight", min_weight, "skip secondary rays weighing <= this [0, 1]");
  app.add_option("--lights", lights, "total number of lights (scene's first, then extra ones)")
      ->default_str("the scene's own");
  app.add_option("--light-range", light_range, "range R (or LO,HI: uniform) of the extra "
                                               "lights of --lights and of the scene's light "
                                               "field; light fades to 0 there")
      ->default_str("the light field's, else none");
  app.add_option("--light-culling", light_culling,
                 "lights each point considers: none (all) | tiled | clustered (per block, per "
                 "depth slice) | bvh (light tree per point); the image is the same");
  app.add_option("--light-lists", light_lists, "how tiled/clustered lists are filled: bvh | "
                                               "brute-force");
  app.add_option("--light-slices", light_slices, "clustered: depth slices per block (1 ... 256)");
  app.add_flag("--animate-lights", o.animate_lights,
               "move every light along its path (frame f at f/30 s), light tree rebuilt each frame");
  app.add_option("--shadows", shadows, "on | off: no shadow rays (every light reaches)");
  app.add_flag("--stage-times", o.render.stage_times,
               "time the kernel's stages (generate, intersect, lights, shade, shadow; ~2 % "
               "slower)");
  app.add_option("--leaf-size", leaf, "BVH maximum primitives per leaf (>= 1)");
  app.add_option("--split", split, "BVH split: sah | midpoint");
  app.add_flag("--no-bvh", o.no_bvh, "no BVH: test every primitive (one leaf holds all)");
  app.add_option("--backend", backend, "serial | omp | tbb");
  app.add_option("--threads", threads, "threads (0 = all hardware threads)");
  app.add_option("--grain", grain, "portions of work per thread (>= 1)");
  app.add_option("--isa", isa, "ray kernels' instruction set: sse41 | avx2 | avx512 (default: "
                              "the widest this CPU runs)");
  app.add_option("--triangle-test", triangle_test,
                 "fast (the thesis's) | watertight (Woop et al. 2013)");
  app.add_option("--packets", packets, "on: coherent rays walk the BVH 16 at a time | off: "
                                       "one by one (the image is the same)");
  app.add_option("--shading-lanes", shading_lanes,
                 "on: Phong hits are shaded 4, 8 or 16 at a time (SIMD) | off: one by one (the "
                 "image is the same)");
  app.add_option("--frames", o.frames, "frames to render (timing: median, min, max)");
  app.add_option("--passes", passes, "render each pixel's samples in this many passes over the "
                                     "image, 1 ... subpixels (progressive)");
  app.add_option("--time-budget", o.time_budget,
                 "seconds per frame: stop after the last pass that fits (0 = all passes)");
  app.add_option("--tile", tile, "square tiles of N pixels handed to threads (0 = threads x "
                                 "grain bands of rows)");
  app.add_option("--block", block, "pixels per side of the blocks a tile is traced in, one "
                                   "batch of rays each (1 ... 256)");
  app.add_option("--output", o.output,
                 "image file: .png .jpg .ppm (sRGB, 8-bit) or .exr .hdr .tif (linear float)")
      ->default_str("none");
  app.add_option("--tonemap", tone_curve, "tone curve of .png .jpg .ppm outputs: none | "
                                          "reinhard | aces (float formats stay linear)");
  app.add_option("--exposure", o.display.exposure, "exposure of display outputs, in stops "
                                                   "(values x 2^stops before the curve)");
  app.add_option("--environment", o.environment,
                 "light from far away: an equirectangular HDR image (.hdr .exr), sky "
                 "(procedural) or none; the background and physically based materials' "
                 "image-based light")
      ->default_str("the scene's");
  app.add_option("--stats", o.stats, "write parameters, times and ray counts to FILE.json")
      ->default_str("none");
  app.add_option("--reference", o.reference, "reference image: print RMSE, PSNR, SSIM")
      ->default_str("none");
  app.add_flag("--interactive", o.interactive.on,
               "open a window and fly through the scene (WASD/arrows, mouse, scroll; F1 "
               "overlay); the image refines while the camera is still");
  app.add_option("--script", o.interactive.script,
                 "--interactive: play the input commands of FILE (wait, key, mouse, "
                 "screenshot, quit ...; README)")
      ->default_str("none");
  app.add_option("--screenshot-key", o.interactive.screenshot_key,
                 "--interactive: the key that saves the image (to --output, else "
                 "rt2cpr-N.png)");
  app.add_option("--target-fps", o.interactive.target_fps,
                 "--interactive: lower the resolution while moving when frames fall under "
                 "this rate (0 = never)");
  app.add_option("--frame-log", o.interactive.frame_log,
                 "--interactive: write one CSV line per frame shown to FILE.csv")
      ->default_str("none");
  std::string rank0 = "render";
  app.add_option("--rank0", rank0, "rt2cpr_mpi: rank 0 renders tiles as well as handing them "
                                   "out (render) or only hands them out (serve)");
  app.add_flag("--quiet", o.quiet, "print only errors");
  app.add_flag("--version", version, "print the version, commit, compiler and ISA, and exit");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return std::nullopt;
  } catch (const CLI::ParseError& e) {
    std::string msg = e.what();
    std::replace(msg.begin(), msg.end(), '\n', ' ');
    throw rt2::Error(msg + " (see --help)");
  }
  if (version) {
    std::cout << rt2::version_line() << "\n";
    return std::nullopt;
  }
  auto given = [&](const char* name) { return app.count(name) > 0; };
  if (given("scene_file")) {
    if (given("--scene"))
      throw rt2::Error("two scenes given: '" + positional_scene + "' and --scene '" + o.scene + "'");
    o.scene = positional_scene;
  }
  check_paths(o, given);
  check_interactive(o, given);

  if (!o.preset.empty()) {
    if (!kPresets.count(o.preset))
      throw rt2::Error("unknown preset '" + o.preset + "' (expected low, middle, hard or veryhard)");
    apply_preset(o.preset, o);
  }
  // Explicit options override the preset.
  if (given("--width")) o.render.width = width;
  if (given("--height")) o.render.height = height;
  if (given("--subpixels")) o.render.subpixels = subpixels;
  if (given("--depth")) o.render.depth = depth;
  if (given("--lights")) o.lights = lights;
  o.render.passes = passes;
  o.render.block = block;
  o.schedule.tile = tile;
  if (!(o.time_budget >= 0.0 && o.time_budget <= 1e9))
    throw rt2::Error("time-budget must be in [0, 1e9] seconds, got " + std::to_string(o.time_budget));
  o.render.min_weight = min_weight;
  o.render.pattern = rt2::parse_pattern(pattern);
  o.isa = rt2::parse_isa(isa);
  if (packets != "on" && packets != "off")
    throw rt2::Error("unknown --packets '" + packets + "' (expected on or off)");
  o.render.packets = packets == "on";
  if (shading_lanes != "on" && shading_lanes != "off")
    throw rt2::Error("unknown --shading-lanes '" + shading_lanes + "' (expected on or off)");
  o.render.shading_lanes = shading_lanes == "on";
  if (triangle_test != "fast" && triangle_test != "watertight")
    throw rt2::Error("unknown triangle test '" + triangle_test + "' (expected fast or watertight)");
  o.render.watertight = triangle_test == "watertight";
  if (light_culling == "none") o.render.light_culling = rt2::LightCulling::none;
  else if (light_culling == "tiled") o.render.light_culling = rt2::LightCulling::tiled;
  else if (light_culling == "clustered") o.render.light_culling = rt2::LightCulling::clustered;
  else if (light_culling == "bvh") o.render.light_culling = rt2::LightCulling::bvh;
  else throw rt2::Error("unknown --light-culling '" + light_culling +
                        "' (expected none, tiled, clustered or bvh)");
  if (light_lists == "bvh") o.render.light_lists = rt2::LightLists::bvh;
  else if (light_lists == "brute-force") o.render.light_lists = rt2::LightLists::brute_force;
  else throw rt2::Error("unknown --light-lists '" + light_lists + "' (expected bvh or brute-force)");
  o.render.light_slices = light_slices;
  if (shadows != "on" && shadows != "off")
    throw rt2::Error("unknown --shadows '" + shadows + "' (expected on or off)");
  o.render.shadows = shadows == "on";
  if (given("--light-range")) o.light_range = parse_range_interval(light_range);
  if (rank0 != "render" && rank0 != "serve")
    throw rt2::Error("unknown --rank0 '" + rank0 + "' (expected render or serve)");
  o.rank0_renders = rank0 == "render";
  if (!rt2::parse_tone_curve(tone_curve, o.display.curve))
    throw rt2::Error("unknown --tonemap '" + tone_curve + "' (expected none, reinhard or aces)");
  if (!(o.display.exposure >= -64.0f && o.display.exposure <= 64.0f))
    throw rt2::Error("exposure must be in [-64, 64] stops, got " + std::to_string(o.display.exposure));
  if (given("--environment") && o.environment.empty())
    throw rt2::Error("--environment needs a file name, sky or none");

  if (split == "sah") o.bvh.split = rt2::Split::sah;
  else if (split == "midpoint") o.bvh.split = rt2::Split::midpoint;
  else throw rt2::Error("unknown split '" + split + "' (expected sah or midpoint)");
  if (leaf < 1 || leaf > UINT32_MAX)
    throw rt2::Error("leaf-size must be in [1, 4294967295], got " + std::to_string(leaf));
  o.bvh.max_leaf_size = static_cast<std::uint32_t>(leaf);
  if (o.no_bvh) o.bvh.max_leaf_size = UINT32_MAX;

  o.schedule.backend = rt2::parse_backend(backend);
  if (threads < 0 || threads > 1024)
    throw rt2::Error("threads must be in [1, 1024] (0 = all hardware threads), got " +
                     std::to_string(threads));
  o.schedule.threads = threads;
  if (grain < 1 || grain > 1'000'000)
    throw rt2::Error("grain must be in [1, 1000000], got " + std::to_string(grain));
  o.schedule.grain = grain;
  if (tile < 0 || tile > 65535)
    throw rt2::Error("tile must be in [1, 65535] (0 = bands of rows), got " + std::to_string(tile));
  if (o.frames < 1 || o.frames > 1'000'000)
    throw rt2::Error("frames must be in [1, 1000000], got " + std::to_string(o.frames));
  if (given("--lights") && (o.lights < 0 || o.lights > 1'000'000))
    throw rt2::Error("lights must be in [0, 1000000], got " + std::to_string(o.lights));
  o.render.validate();
  return o;
}

}  // namespace rt2cpr
