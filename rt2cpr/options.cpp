// rt2cpr/options.cpp — CLI11 definitions, presets (SPEC "presets") and validation.
//
// CLI11 formats --help and binds each option to its variable, but never judges a command
// line: the words are checked first (canonical_words) and handed to CLI11 in a form it
// reads without a complaint of its own, and numbers are bound as text and converted here,
// so that every message about the command line is rt2cpr's.
#include "rt2cpr/options.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <charconv>
#include <climits>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <string_view>
#include <type_traits>
#include <vector>

#include "rt2/base/error.h"
#include "rt2/image/image_codec.h"
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

// ---- the words of the command line ------------------------------------------------------

// What the value of an option is, by its type name in --help: "--scene needs a value (a
// file)".
std::string value_kind(const CLI::Option& opt) {
  static const std::map<std::string, std::string> kinds = {
      {"INT", "an integer"},  {"FLOAT", "a number"},   {"FILE", "a file"},
      {"TEXT", "a name"},     {"KEY", "a key name"},   {"R|LO,HI", "R or LO,HI"},
      {"FILE|sky|none", "a file, sky or none"}};
  const auto it = kinds.find(opt.get_type_name());
  return it != kinds.end() ? it->second : "a value";
}

bool is_flag(const CLI::Option& opt) { return opt.get_items_expected_max() == 0; }

// Optimal string alignment distance: an insertion, a deletion, a substitution or a swap of
// two neighbours counts 1 ("widht" is 1 from "width").
std::size_t typo_distance(std::string_view a, std::string_view b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1,
                          d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

// `word` without its leading dashes: ASCII '-', and the dashes and minus sign (U+2010 ...
// U+2015, U+2212) that a word processor or a web page puts in place of "--". `unicode`
// tells whether there was one of those.
std::string_view undashed(std::string_view word, bool& unicode) {
  unicode = false;
  for (;;) {
    if (word.starts_with('-')) {
      word.remove_prefix(1);
    } else if (word.size() >= 3 && ((word.starts_with("\xE2\x80") && word[2] >= '\x90' &&
                                     word[2] <= '\x95') ||
                                    word.starts_with("\xE2\x88\x92"))) {
      word.remove_prefix(3);
      unicode = true;
    } else {
      return word;
    }
  }
}

// A number ("-1", "-0.5", "2"): an option's value, never an option.
bool looks_like_number(const std::string& word) {
  if (word.empty() || std::isspace(static_cast<unsigned char>(word[0]))) return false;
  char* end = nullptr;
  std::strtod(word.c_str(), &end);
  return end == word.c_str() + word.size();
}

// The command line's options by name ("--width", "-h"), in the order --help lists them.
class KnownOptions {
 public:
  explicit KnownOptions(const CLI::App& app) {
    for (const CLI::Option* opt : app.get_options()) {
      for (const std::string& n : opt->get_lnames()) {
        by_name_["--" + n] = opt;
        long_names_.push_back(n);
      }
      for (const std::string& n : opt->get_snames()) by_name_["-" + n] = opt;
    }
  }

  const CLI::Option* find(const std::string& name) const {
    const auto it = by_name_.find(name);
    return it != by_name_.end() ? it->second : nullptr;
  }

  // The long option closest to `name` (given without dashes), as "--name", or "": within 1
  // edit of options of up to 4 letters, 2 up to 8, 3 beyond; or else the only option that
  // begins with `name` (of 3 letters or more: "leaf" for --leaf-size).
  std::string closest(std::string_view name) const {
    if (name.size() > 64) return "";  // not a typo; and the distance is quadratic
    std::string best, only_prefix;
    std::size_t best_d = SIZE_MAX;
    int prefixes = 0;
    for (const std::string& known : long_names_) {
      const std::size_t d = typo_distance(name, known);
      const std::size_t limit = known.size() <= 4 ? 1 : known.size() <= 8 ? 2 : 3;
      if (d <= limit && d < known.size() && d < best_d) {
        best_d = d;
        best = known;
      }
      if (name.size() >= 3 && known.starts_with(name)) {
        ++prefixes;
        only_prefix = known;
      }
    }
    if (best.empty() && prefixes == 1) best = only_prefix;
    return best.empty() ? "" : "--" + best;
  }

 private:
  std::map<std::string, const CLI::Option*> by_name_;
  std::vector<std::string> long_names_;
};

std::string in_quotes(const std::string& s) { return "\"" + s + "\""; }

// "unknown option WORD; did you mean --NAME?", or "unknown option WORD (see --help)".
rt2::Error unknown_option(const KnownOptions& known, const std::string& word) {
  bool unicode = false;
  const std::string_view bare = undashed(word, unicode);
  const std::string name(bare.substr(0, bare.find('=')));
  const std::string shown = name.empty() ? word : word.substr(0, word.find('='));
  const std::string guess = known.closest(name);
  return rt2::Error("unknown option " + shown +
                    (guess.empty() ? " (see --help)" : "; did you mean " + guess + "?"));
}

// The command line's words (argv[1] ...), checked and put in the form CLI11 reads without
// a complaint of its own: each option by its name, each value option's value as the next
// word, and the scene, if any, after "--". Throws rt2::Error naming the first problem:
// - an unknown option ("--subpixel; did you mean --subpixels?"), also a word that is not
//   an option but looks like one (-width, a Unicode dash, a bare "width");
// - a value option at the end, or followed by another option (a value never starts with
//   "--": "--scene --width 5" does not load a scene named "--width");
// - a flag given a value (--quiet=yes, --quiet 1);
// - an option given twice, or a number after its value ("--width 5 6");
// - a second scene.
// Negative numbers are values: "--exposure -1".
std::vector<std::string> canonical_words(const CLI::App& app,
                                         const std::vector<std::string>& words) {
  const KnownOptions known(app);
  std::vector<std::string> out;
  std::map<const CLI::Option*, std::vector<std::string>> values;
  std::vector<std::pair<const CLI::Option*, std::string>> given;  // in order, and each name
  std::string scene;
  bool have_scene = false;
  const CLI::Option* before = nullptr;  // the option the last word named or was the value of

  const auto add_scene = [&](const std::string& word) {
    if (have_scene)
      throw rt2::Error("two scenes given: " + in_quotes(scene) + " and " + in_quotes(word));
    scene = word;
    have_scene = true;
  };
  for (std::size_t i = 0; i < words.size(); ++i) {
    const std::string& word = words[i];
    if (word == "--") {  // the rest are scenes, whatever they look like
      for (++i; i < words.size(); ++i) add_scene(words[i]);
      break;
    }
    const bool dashed = word.size() > 1 && word[0] == '-' && !looks_like_number(word);
    if (!dashed) {
      // A number right after an option's value or a flag is a second value of that option.
      if (before && looks_like_number(word)) {
        if (is_flag(*before))
          throw rt2::Error(given.back().second + " takes no value, got " + in_quotes(word));
        values[before].push_back(word);
        before = nullptr;
        continue;
      }
      bool unicode = false;
      const std::string_view bare = undashed(word, unicode);
      // A word with a Unicode dash, or a bare word that could not be a file name, close to
      // an option's name.
      if (unicode || word.find_first_of("./") == std::string::npos) {
        const std::string guess = known.closest(bare.substr(0, bare.find('=')));
        if (!guess.empty() && unicode) throw unknown_option(known, word);
        if (!guess.empty())
          throw rt2::Error("unexpected argument " + in_quotes(word) + "; did you mean " + guess +
                           "?");
      }
      add_scene(word);
      before = nullptr;
      continue;
    }
    const std::size_t eq = word.starts_with("--") ? word.find('=') : std::string::npos;
    const std::string name = word.substr(0, eq);
    const CLI::Option* opt = known.find(name);
    if (!opt) throw unknown_option(known, word);
    given.emplace_back(opt, name);
    before = opt;
    if (is_flag(*opt)) {
      if (eq != std::string::npos)
        throw rt2::Error(name + " takes no value, got " + in_quotes(word.substr(eq + 1)));
      out.push_back(name);
      continue;
    }
    const std::string needs = name + " needs a value (" + value_kind(*opt) + ")";
    if (eq == std::string::npos && i + 1 == words.size()) throw rt2::Error(needs);
    const std::string value = eq != std::string::npos ? word.substr(eq + 1) : words[++i];
    const std::string value_name = value.substr(0, value.find('='));
    if (known.find(value_name))
      throw rt2::Error(needs + ", got the option " + value_name);
    if (value.starts_with("--"))
      throw rt2::Error(needs + ", got " + in_quotes(value) + " (a value may not start with --)");
    values[opt].push_back(value);
    out.push_back(name);
    out.push_back(value);
  }
  for (const auto& [opt, name] : given) {
    const std::vector<std::string>& v = values[opt];
    if (v.size() < 2) continue;
    std::string all;
    for (const std::string& s : v) all += (all.empty() ? "" : " ") + s;
    throw rt2::Error(name + " takes one value, got " + std::to_string(v.size()) + " (" +
                     in_quotes(all) + ")");
  }
  if (have_scene) {
    out.push_back("--");
    out.push_back(scene);
  }
  return out;
}

// ---- values -----------------------------------------------------------------------------

// `text` as a decimal integer in [lo, hi]: an optional sign, then digits and nothing else
// (no blanks, no 0x, no exponent: "010" is ten). Throws naming `flag` otherwise.
template <class T>
T integer_of(const char* flag, const std::string& text, T lo = std::numeric_limits<T>::min(),
             T hi = std::numeric_limits<T>::max()) {
  const std::size_t sign = !text.empty() && (text[0] == '+' || text[0] == '-') ? 1 : 0;
  const std::string_view digits = std::string_view(text).substr(sign);
  if (digits.empty() || !std::all_of(digits.begin(), digits.end(),
                                     [](char c) { return c >= '0' && c <= '9'; }))
    throw rt2::Error(std::string(flag) + " needs an integer, got " + in_quotes(text));
  const std::string_view number = std::string_view(text).substr(text[0] == '+' ? 1 : 0);
  T v{};
  const auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), v);
  if (ec != std::errc() || end != number.data() + number.size() || v < lo || v > hi)
    throw rt2::Error(std::string(flag) + " needs an integer from " + std::to_string(lo) + " to " +
                     std::to_string(hi) + ", got " + in_quotes(text));
  return v;
}

// `text` as a number: decimal with an optional exponent, or nan or inf (which each
// option's own check then refuses). Throws naming `flag` otherwise.
double number_of(const char* flag, const std::string& text) {
  char* end = nullptr;
  const bool plain = !text.empty() && !std::isspace(static_cast<unsigned char>(text[0])) &&
                     text.find_first_of("xX") == std::string::npos;
  const double v = plain ? std::strtod(text.c_str(), &end) : 0.0;
  if (!plain || end != text.c_str() + text.size())
    throw rt2::Error(std::string(flag) + " needs a number, got " + in_quotes(text));
  return v;
}

// A default as --help shows it: 0.01, 30, 0.
std::string shown(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// ---- files ------------------------------------------------------------------------------

using Named = std::pair<const char*, const std::string*>;  // an option and its file

// An output file (`flag` `path`) that names one of `others` is refused: writing it would
// overwrite an input or another output.
void refuse_same_file(const char* flag, const std::string& path, std::initializer_list<Named> others) {
  for (const auto& [other_flag, other] : others)
    if (!other->empty() && rt2::io::same_file(path, *other))
      throw rt2::Error(std::string(flag) + " " + path + " is the same file as " + other_flag + " " +
                       *other);
}

// The image formats rt2cpr documents (--help, README.md); any other extension is asked of
// the image codec.
constexpr const char* kImageExtensions[] = {".png", ".jpg", ".jpeg", ".ppm",
                                            ".exr", ".hdr", ".tif",  ".tiff"};

// An image output (`flag` `path`) whose extension names a format rt2 writes. The message
// names the user's path (the codec's own reason names a file of its making).
void check_image_extension(const char* flag, const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const std::string expected = "(.png, .jpg, .ppm: 8-bit sRGB; .exr, .hdr, .tif: linear float)";
  if (ext.empty() || ext == ".")
    throw rt2::Error(std::string(flag) + " " + path + ": no extension to choose the image format " +
                     expected);
  if (std::find(std::begin(kImageExtensions), std::end(kImageExtensions), ext) !=
      std::end(kImageExtensions))
    return;
  std::string why;
  try {
    why = rt2::image_codec().can_encode(ext);
  } catch (const rt2::Error&) {
    return;  // no codec: rt2::check_writable_image says so
  }
  if (!why.empty())
    throw rt2::Error(std::string(flag) + " " + path + ": unsupported image format '" + ext + "' " +
                     expected);
}

// The files named on the command line: none empty, image outputs of a known format, and
// the statistics and the image never overwrite an input or each other.
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
  if (!o.output.empty()) {
    check_image_extension("--output", o.output);
    refuse_same_file("--output", o.output,
                     {{"--scene", &o.scene}, {"--reference", &o.reference}, {"--camera", &o.camera},
                      {"--environment", &o.environment}});
  }
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
  std::string pattern = "grid", split = "sah", backend = "omp", triangle_test = "fast",
              isa = rt2::isa_name(o.isa), packets = "on", shading_lanes = "on", positional_scene,
              light_culling = "clustered", light_lists = "bvh", shadows = "on",
              tone_curve = "none";
  std::string light_range;
  bool version = false;

  // Numbers as given; converted after parsing (integer_of, number_of) when given.
  std::map<std::string, std::string> numbers;
  const auto integer = [&](const char* name, const std::string& default_shown,
                           const std::string& help) {
    return app.add_option(name, numbers[name], help)->type_name("INT")->default_str(default_shown);
  };
  const auto real = [&](const char* name, double default_value, const std::string& help) {
    return app.add_option(name, numbers[name], help)
        ->type_name("FLOAT")
        ->default_str(shown(default_value));
  };
  const auto file = [&](const char* name, std::string& target, const std::string& help) {
    return app.add_option(name, target, help)->type_name("FILE");
  };

  file("scene_file", positional_scene, "the scene, as with --scene")->default_str("");
  file("--scene", o.scene, "scene file (.toml), mesh (.obj) or glTF 2.0 (.gltf/.glb)")
      ->default_str("built-in scene");
  file("--camera", o.camera, "the camera of a TOML file holding a [camera] table (what the "
                             "viewer's C key prints)")
      ->default_str("the scene's");
  app.add_option("--preset", o.preset, "low | middle | hard | veryhard")->default_str("none");
  integer("--width", std::to_string(o.render.width), "image width in pixels");
  integer("--height", std::to_string(o.render.height), "image height in pixels");
  integer("--subpixels", std::to_string(o.render.subpixels), "samples per pixel (>= 1)");
  app.add_option("--pattern", pattern, "subpixel pattern: grid | circle");
  integer("--depth", std::to_string(o.render.depth),
          "recursion depth (0 = no reflection/refraction rays)");
  real("--min-weight", o.render.min_weight, "skip secondary rays weighing <= this [0, 1]");
  integer("--lights", "the scene's own", "total number of lights (scene's first, then extra ones)");
  app.add_option("--light-range", light_range, "range R (or LO,HI: uniform) of the extra "
                                               "lights of --lights and of the scene's light "
                                               "field; light fades to 0 there")
      ->type_name("R|LO,HI")
      ->default_str("the light field's, else none");
  app.add_option("--light-culling", light_culling,
                 "lights each point considers: none (all) | tiled | clustered (per block, per "
                 "depth slice) | bvh (light tree per point); the image is the same");
  app.add_option("--light-lists", light_lists, "how tiled/clustered lists are filled: bvh | "
                                               "brute-force");
  integer("--light-slices", std::to_string(o.render.light_slices),
          "clustered: depth slices per block (1 ... 256)");
  app.add_flag("--animate-lights", o.animate_lights,
               "move every light along its path (frame f at f/30 s), light tree rebuilt each frame");
  real("--time", o.pose.seconds, "render the scene's animation at this many seconds (the "
                                 "first frame; each next one 1/fps later)");
  real("--fps", o.fps, "frames per second of an animated scene over --frames (> 0)");
  app.add_option("--animation", o.pose.animation,
                 "which of a glTF's animations plays: its name or index")
      ->type_name("NAME|INDEX")
      ->default_str("the first");
  app.add_option("--shadows", shadows, "on | off: no shadow rays (every light reaches)");
  app.add_flag("--stage-times", o.render.stage_times,
               "time the kernel's stages (generate, intersect, lights, shade, shadow; ~2 % "
               "slower)");
  integer("--leaf-size", std::to_string(o.bvh.max_leaf_size),
          "BVH maximum primitives per leaf (>= 1)");
  app.add_option("--split", split, "BVH split: sah | midpoint");
  app.add_flag("--no-bvh", o.no_bvh, "no BVH: test every primitive (one leaf holds all)");
  app.add_option("--backend", backend, "serial | omp | tbb");
  integer("--threads", std::to_string(o.schedule.threads), "threads (0 = all hardware threads)");
  integer("--grain", std::to_string(o.schedule.grain), "portions of work per thread (>= 1)");
  app.add_option("--isa", isa, "ray kernels' instruction set: sse41 | avx2 | avx512 (default: "
                              "the widest this CPU runs)");
  app.add_option("--triangle-test", triangle_test,
                 "fast (the thesis's) | watertight (Woop et al. 2013)");
  app.add_option("--packets", packets, "on: coherent rays walk the BVH 16 at a time | off: "
                                       "one by one (the image is the same)");
  app.add_option("--shading-lanes", shading_lanes,
                 "on: Phong and PBR hits, a point's lights and the misses' sky are shaded 4, 8 or 16 "
                 "at a time (SIMD) | off: one by one (the image is the same)");
  integer("--frames", std::to_string(o.frames), "frames to render (timing: median, min, max)");
  integer("--passes", std::to_string(o.render.passes),
          "render each pixel's samples in this many passes over the image, 1 ... subpixels "
          "(progressive)");
  real("--time-budget", o.time_budget,
       "seconds per frame: stop after the last pass that fits (0 = all passes)");
  integer("--tile", std::to_string(o.schedule.tile),
          "square tiles of N pixels handed to threads (0 = threads x grain bands of rows)");
  integer("--block", std::to_string(o.render.block),
          "pixels per side of the blocks a tile is traced in, one batch of rays each (1 ... 256)");
  file("--output", o.output,
       "image file: .png .jpg .ppm (sRGB, 8-bit) or .exr .hdr .tif (linear float)")
      ->default_str("none");
  app.add_option("--tonemap", tone_curve, "tone curve of .png .jpg .ppm outputs: none | "
                                          "reinhard | aces (float formats stay linear)");
  real("--exposure", o.display.exposure,
       "exposure of display outputs, in stops (values x 2^stops before the curve)");
  app.add_option("--environment", o.environment,
                 "light from far away: an equirectangular HDR image (.hdr .exr), sky "
                 "(procedural) or none; the background and physically based materials' "
                 "image-based light")
      ->type_name("FILE|sky|none")
      ->default_str("the scene's");
  app.add_flag("--allow-outside-assets", o.assets.allow_outside_assets,
               "files a scene refers to (textures, MTL libraries, glTF buffers and images) may "
               "lie outside the folder of the file that names them");
  integer("--max-texture-pixels", std::to_string(o.assets.max_image_pixels),
          "the most pixels (width x height) a texture or environment image may have (>= 1)");
  file("--stats", o.stats, "write parameters, times and ray counts to FILE.json")
      ->default_str("none");
  file("--reference", o.reference, "reference image: print RMSE, PSNR, SSIM")
      ->default_str("none");
  app.add_flag("--interactive", o.interactive.on,
               "open a window and fly through the scene (WASD/arrows, mouse, scroll; F1 "
               "overlay); the image refines while the camera is still");
  file("--script", o.interactive.script,
       "--interactive: play the input commands of FILE (wait, key, mouse, screenshot, quit "
       "...; README)")
      ->default_str("none");
  app.add_option("--screenshot-key", o.interactive.screenshot_key,
                 "--interactive: the key that saves the image (to --output, else "
                 "rt2cpr-N.png)")
      ->type_name("KEY");
  real("--target-fps", o.interactive.target_fps,
       "--interactive: lower the resolution while moving when frames fall under this rate (0 "
       "= never)");
  file("--frame-log", o.interactive.frame_log,
       "--interactive: write one CSV line per frame shown to FILE.csv")
      ->default_str("none");
  std::string rank0 = "render";
  app.add_option("--rank0", rank0, "rt2cpr_mpi: rank 0 renders tiles as well as handing them "
                                   "out (render) or only hands them out (serve)");
  app.add_flag("--quiet", o.quiet, "print only errors");
  app.add_flag("--version", version, "print the version, commit, compiler and ISA, and exit");

  const std::vector<std::string> words(argv + std::min(argc, 1), argv + argc);
  std::vector<std::string> canonical = canonical_words(app, words);
  std::reverse(canonical.begin(), canonical.end());  // CLI11 reads the words from the back
  try {
    app.parse(std::move(canonical));
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return std::nullopt;
  } catch (const CLI::ParseError&) {
    // canonical_words refuses everything CLI11 would: this is a word it let through.
    throw rt2::Error("cannot read the command line (see --help)");
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
  if (given("scene_file") && positional_scene.empty()) throw rt2::Error("empty scene file name");
  // The preset first: explicit options override it.
  if (!o.preset.empty()) {
    if (!kPresets.count(o.preset))
      throw rt2::Error("unknown preset '" + o.preset + "' (expected low, middle, hard or veryhard)");
    apply_preset(o.preset, o);
  }
  const auto int_value = [&](const char* name, int& target) {
    if (given(name)) target = integer_of<int>(name, numbers[name]);
  };
  const auto float_value = [&](const char* name, auto& target) {
    using T = std::remove_reference_t<decltype(target)>;
    if (given(name)) target = static_cast<T>(number_of(name, numbers[name]));
  };
  int_value("--width", o.render.width);
  int_value("--height", o.render.height);
  int_value("--subpixels", o.render.subpixels);
  int_value("--depth", o.render.depth);
  int_value("--lights", o.lights);
  int_value("--light-slices", o.render.light_slices);
  int_value("--threads", o.schedule.threads);
  int_value("--grain", o.schedule.grain);
  int_value("--frames", o.frames);
  int_value("--passes", o.render.passes);
  int_value("--tile", o.schedule.tile);
  int_value("--block", o.render.block);
  float_value("--min-weight", o.render.min_weight);
  float_value("--time-budget", o.time_budget);
  float_value("--exposure", o.display.exposure);
  float_value("--target-fps", o.interactive.target_fps);
  float_value("--time", o.pose.seconds);
  float_value("--fps", o.fps);
  if (given("--leaf-size"))
    o.bvh.max_leaf_size = integer_of<std::uint32_t>("--leaf-size", numbers["--leaf-size"], 1);
  if (given("--max-texture-pixels"))
    o.assets.max_image_pixels =
        integer_of<std::uint64_t>("--max-texture-pixels", numbers["--max-texture-pixels"], 1);
  check_paths(o, given);
  check_interactive(o, given);

  if (!(std::abs(o.pose.seconds) <= 1e9))
    throw rt2::Error("time must be in [-1e9, 1e9] seconds, got " + std::to_string(o.pose.seconds));
  if (!(o.fps >= 1e-3 && o.fps <= 1e6))
    throw rt2::Error("fps must be in [0.001, 1000000], got " + std::to_string(o.fps));
  if (given("--animation") && o.pose.animation.empty())
    throw rt2::Error("--animation needs a name or an index");
  if (!(o.time_budget >= 0.0 && o.time_budget <= 1e9))
    throw rt2::Error("time-budget must be in [0, 1e9] seconds, got " + std::to_string(o.time_budget));
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
  if (o.no_bvh) o.bvh.max_leaf_size = UINT32_MAX;

  o.schedule.backend = rt2::parse_backend(backend);
  if (o.schedule.threads < 0 || o.schedule.threads > 1024)
    throw rt2::Error("threads must be in [1, 1024] (0 = all hardware threads), got " +
                     std::to_string(o.schedule.threads));
  if (o.schedule.grain < 1 || o.schedule.grain > 1'000'000)
    throw rt2::Error("grain must be in [1, 1000000], got " + std::to_string(o.schedule.grain));
  if (o.schedule.tile < 0 || o.schedule.tile > 65535)
    throw rt2::Error("tile must be in [1, 65535] (0 = bands of rows), got " +
                     std::to_string(o.schedule.tile));
  if (o.frames < 1 || o.frames > 1'000'000)
    throw rt2::Error("frames must be in [1, 1000000], got " + std::to_string(o.frames));
  if (given("--lights") && (o.lights < 0 || o.lights > 1'000'000))
    throw rt2::Error("lights must be in [0, 1000000], got " + std::to_string(o.lights));
  o.render.validate();
  return o;
}

}  // namespace rt2cpr
