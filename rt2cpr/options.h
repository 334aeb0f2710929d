// rt2cpr/options.h — rt2cpr's command line: every knob of the renderer, the presets, and
// their validation.
#pragma once

#include <optional>
#include <string>

#include "rt2/base/asset_policy.h"
#include "rt2/bvh/node.h"
#include "rt2/base/isa.h"
#include "rt2/render/renderer.h"
#include "rt2/scene/scene.h"
#include "rt2/render/schedule.h"
#include "rt2/image/tonemap.h"

namespace rt2cpr {

// The interactive viewer (rt2cpr/viewer/viewer.h).
struct Interactive {
  bool on = false;           // --interactive: a window instead of files
  std::string script;        // --script: input commands to play (viewer/script.h); empty: none
  std::string screenshot_key = "F12";  // --screenshot-key: the key that saves the image
  double target_fps = 30.0;  // --target-fps: moving frames below it lower the resolution
  std::string frame_log;     // --frame-log: one CSV line per frame shown; empty: none
};

struct Options {
  std::string scene;   // a .toml scene or an .obj; empty: the built-in scene
  std::string camera;  // --camera: a TOML file holding a [camera] table; empty: the scene's
  std::string preset;  // low | middle | hard | veryhard, or empty
  rt2::RenderSettings render;
  int lights = -1;     // total light count; -1: the scene's own lights
  std::optional<rt2::RangeInterval> light_range;  // --light-range (rt2::set_light_count)
  bool animate_lights = false;  // frame f: lights where their paths are at f / 30 s
  // A glTF's animation (--animation: its name or index; empty: the first) at --time
  // seconds for the first frame, each further frame 1 / --fps later.
  rt2::ScenePose pose;
  double fps = 30.0;
  rt2::BvhConfig bvh;
  rt2::Isa isa = rt2::best_isa();  // the ray kernels' instruction set (--isa)
  bool no_bvh = false;  // one leaf holding every primitive (brute force)
  rt2::Schedule schedule;
  int frames = 1;
  double time_budget = 0.0;  // seconds per frame for its passes; 0: every pass
  std::string output;  // image file; empty: not written
  rt2::Display display;  // exposure and tone curve of display outputs (.png ...)
  // --environment: an HDR image file, "sky" (procedural) or "none"; empty: the scene's.
  std::string environment;
  // What the scene's files may refer to and how large its images may be
  // (--allow-outside-assets, --max-texture-pixels).
  rt2::AssetPolicy assets;
  std::string stats;   // JSON file; empty: not written
  std::string reference;  // reference image to compare against; empty: none
  bool quiet = false;
  // --rank0 (rt2cpr_mpi): rank 0 renders tiles as well as handing them out (true), or only
  // hands them out (false: when serving many ranks is a full-time job).
  bool rank0_renders = true;
  Interactive interactive;  // --interactive and its options
};

// Parses argv. Returns nullopt when --help or --version was printed (exit 0). Throws
// rt2::Error with a one-line message naming the option for any bad option or value (an
// unknown option, with the closest known one; a missing value, or another option in its
// place; an option given twice; a number that is not one), an empty file name, an image
// output of an unknown format, a statistics file not named .json, and a statistics or image
// file that names an input (the scene, the reference) or the other output.
std::optional<Options> parse_options(int argc, char** argv);

}  // namespace rt2cpr
