// tests/rt2/io/hostile_test.cpp — the loader against the hostile inputs of tests/hostile/: every
// case is loaded with rt2::load_scene and must end as its <case>.expect file says, one test
// per case (Case/HostileInputs.Loads/<case>).
//
// The contract checked: an error is an rt2::Error (nothing else escapes, nothing crashes)
// whose message is one line, starts with the file it is about (and "file:LINE:" when the case
// gives a line) and contains the expected text; a case that loads does so without throwing,
// with the expected warnings on stderr (or none) and the expected counts. The .expect format
// is documented in tests/hostile/README.md; the cases are made by tests/hostile/generate.py.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>
#include <random>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rt2/base/error.h"
#include "rt2/io/scene_io.h"
#include "tests/rt2/temp_dir.h"

#ifndef RT2_SOURCE_DIR
#error "the build defines RT2_SOURCE_DIR as the repository root"
#endif

namespace rt2 {
namespace {

namespace fs = std::filesystem;

const fs::path& hostile_dir() {
  static const fs::path dir = fs::path(std::string(RT2_SOURCE_DIR) + "/tests/hostile");
  return dir;
}

// The cases whose inputs are megabytes are not committed: "generated/<file>" in a .expect
// file names one of these, written on first use into a TempDir (removed at exit). tests/hostile/generate.py describes the same contents.
const std::string kCamera = "[camera]\nposition = [0, 1, 5]\nlook_at = [0, 0, 0]\n";
const std::string kRed = "[materials.red]\ndiffuse = [1, 0, 0]\n";  // lines 4-5
const std::string kSphere = "[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"red\"\n";
const std::string kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
constexpr std::size_t kMiB = std::size_t{1} << 20;

std::string make_generated(const std::string& file) {
  if (file == "spheres_100000.toml") {
    std::string s = kCamera + "[materials.m]\n";
    for (int i = 0; i < 100000; ++i)
      s += "[[spheres]]\ncenter=[" + std::to_string(i % 100) + "," +
           std::to_string(i / 100 % 100) + "," + std::to_string(i / 10000) +
           "]\nradius=0.4\nmaterial='m'\n";
    return s;
  }
  if (file == "long_line_toml_comment.toml")
    return kCamera + kRed + "#" + std::string(kMiB, 'x') + "\n" + kSphere;
  if (file == "long_line_toml_key.toml") return kCamera + std::string(kMiB, 'k') + " = 1\n";
  if (file == "long_line_obj_comment.obj") return "#" + std::string(kMiB, 'x') + "\n" + kTriangle;
  if (file == "long_line_obj_vertex.obj") {
    std::string s = "v 0 0 0";
    for (std::size_t i = 0; i < kMiB / 4; ++i) s += " 0.5";
    return s + "\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  }
  const auto polygon = [](std::size_t n, auto&& corner) {
    std::string s;
    for (std::size_t k = 0; k < n; ++k) {
      const auto [x, y] = corner(k);
      s += "v " + std::to_string(x) + " " + std::to_string(y) + " 0\n";
    }
    s += "f";
    for (std::size_t k = 1; k <= n; ++k) s += " " + std::to_string(k);
    return s + "\n";
  };
  if (file == "obj_polygon_100000_corners.obj") {
    return polygon(100000, [](std::size_t k) {
      const double a = 2 * 3.14159265358979 * double(k) / 100000;
      return std::pair(std::cos(a), std::sin(a));
    });
  }
  if (file == "obj_polygon_random_20000.obj") {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    return polygon(20000, [&](std::size_t) { return std::pair(u(rng), u(rng)); });
  }
  if (file == "mtl_1000000_materials.obj")
    return "mtllib mtl_1000000_materials.mtl\nusemtl m999999\n" + kTriangle;
  if (file == "mtl_1000000_materials.mtl") {
    std::string s;
    for (int i = 0; i < 1000000; ++i) s += "newmtl m" + std::to_string(i) + "\nKd 0.5\n";
    return s;
  }
  return {};
}

// Files that must not be held in memory: made in place.
bool make_generated_in_place(const std::string& file, const std::string& path) {
  if (file == "obj_zeros_2_gib.obj") {  // sparse, as `truncate -s 2G` makes it
    std::ofstream(path).close();
    fs::resize_file(path, std::uintmax_t{2} << 30);
    return true;
  }
  return false;
}

std::string generated_path(const std::string& file) {
  static const test::TempDir dir("hostile");
  const std::string path = dir.path(file);
  if (!fs::exists(path) && !make_generated_in_place(file, path)) {
    const std::string content = make_generated(file);
    if (content.empty()) return path;  // unknown: loading fails, the case says why
    dir.write(file, content);
    // An OBJ's MTL library, if it has one.
    const std::string mtl = fs::path(file).replace_extension(".mtl").string();
    const std::string mtl_content = file.ends_with(".obj") ? make_generated(mtl) : "";
    if (!mtl_content.empty()) dir.write(mtl, mtl_content);
  }
  return path;
}

// A path named in a .expect file: "generated/<file>" (above), relative to tests/hostile/, or
// absolute.
std::string case_path(const std::string& name) {
  constexpr std::string_view kGenerated = "generated/";
  if (name.rfind(kGenerated, 0) == 0) return generated_path(name.substr(kGenerated.size()));
  return fs::path(name).is_absolute() ? name : (hostile_dir() / name).string();
}

// One <case>.expect file, parsed. Keys that may repeat (warning, material) keep every value.
struct Expectation {
  std::string name;  // the case: the .expect file's stem
  std::multimap<std::string, std::string> keys;
  std::vector<std::string> problems;  // in the file itself: unknown keys, bad lines

  bool has(const std::string& k) const { return keys.count(k) > 0; }
  std::string get(const std::string& k) const {
    const auto it = keys.find(k);
    return it == keys.end() ? std::string() : it->second;
  }
  std::vector<std::string> all(const std::string& k) const {
    std::vector<std::string> out;
    for (auto [it, end] = keys.equal_range(k); it != end; ++it) out.push_back(it->second);
    return out;
  }
};

const std::vector<std::string> kKnownKeys = {
    "load",    "error", "line",       "file",     "ok",      "warning", "quiet",
    "spheres", "faces", "degenerate", "material", "diffuse", "specular"};

std::string trim(std::string_view s) {
  const std::size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string_view::npos) return {};
  return std::string(s.substr(a, s.find_last_not_of(" \t\r") - a + 1));
}

// "key: value" lines; blank lines and lines starting with '#' are skipped.
Expectation parse_expect(const fs::path& path) {
  Expectation e;
  e.name = path.stem().string();
  std::ifstream in(path, std::ios::binary);
  std::string line;
  while (std::getline(in, line)) {
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    const std::size_t colon = t.find(':');
    const std::string key = trim(t.substr(0, std::min(colon, t.size())));
    if (colon == std::string::npos ||
        std::find(kKnownKeys.begin(), kKnownKeys.end(), key) == kKnownKeys.end()) {
      e.problems.push_back("bad line: " + t);
      continue;
    }
    e.keys.emplace(key, trim(t.substr(colon + 1)));
  }
  if (!e.has("load")) e.problems.push_back("no 'load:' line");
  if (e.has("error") == e.has("ok")) e.problems.push_back("needs exactly one of error: and ok:");
  return e;
}

std::vector<Expectation> all_cases() {
  std::vector<Expectation> cases;
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(hostile_dir(), ec))
    if (entry.path().extension() == ".expect") cases.push_back(parse_expect(entry.path()));
  std::sort(cases.begin(), cases.end(),
            [](const Expectation& a, const Expectation& b) { return a.name < b.name; });
  return cases;
}

// What loading a case did: the scene or the error message, and everything on stderr.
struct Outcome {
  bool loaded = false;
  Scene scene;
  std::string error;  // what() of the rt2::Error
  std::string other;  // a description of any other exception
  std::string err;    // stderr
};

Outcome load(const std::string& path) {
  Outcome o;
  testing::internal::CaptureStderr();
  try {
    o.scene = load_scene(path);
    o.loaded = true;
  } catch (const Error& e) {
    o.error = e.what();
  } catch (const std::exception& e) {
    o.other = std::string("std::exception: ") + e.what();
  } catch (...) {
    o.other = "an exception that is not a std::exception";
  }
  o.err = testing::internal::GetCapturedStderr();
  return o;
}

bool contains(std::string_view s, std::string_view part) {
  return s.find(part) != std::string_view::npos;
}

void check_error(const Expectation& e, const Outcome& o) {
  ASSERT_FALSE(o.loaded) << "loaded, but expected an error containing: " << e.get("error");
  EXPECT_FALSE(contains(o.error, "\n") || contains(o.error, "\r")) << "not one line: " << o.error;
  const std::string file = case_path(e.has("file") ? e.get("file") : e.get("load"));
  const std::string prefix = file + ":" + (e.has("line") ? e.get("line") + ":" : "");
  EXPECT_EQ(o.error.rfind(prefix, 0), 0u) << "expected to start with '" << prefix
                                          << "': " << o.error;
  EXPECT_TRUE(contains(o.error, e.get("error")))
      << "expected '" << e.get("error") << "' in: " << o.error;
}

std::size_t face_count(const Scene& s) {
  std::size_t n = 0;
  for (const Mesh& m : s.meshes) n += m.faces.size();
  return n;
}

void check_ok(const Expectation& e, const Outcome& o) {
  ASSERT_TRUE(o.loaded) << "expected to load, but: " << o.error;
  for (const std::string& w : e.all("warning"))
    EXPECT_TRUE(contains(o.err, "warning: ") && contains(o.err, w))
        << "expected the warning '" << w << "' on stderr, got: " << o.err;
  if (e.has("quiet")) {
    EXPECT_EQ(o.err, "") << "expected nothing on stderr";
  }
  if (e.has("spheres")) {
    EXPECT_EQ(std::to_string(o.scene.spheres.size()), e.get("spheres"));
  }
  if (e.has("faces")) {
    EXPECT_EQ(std::to_string(face_count(o.scene)), e.get("faces"));
  }
  if (e.has("degenerate")) {
    EXPECT_EQ(std::to_string(o.scene.degenerate_triangles), e.get("degenerate"));
  }
  for (const std::string& m : e.all("material"))
    EXPECT_GE(o.scene.find_material(m), 0) << "no material named '" << m << "'";
  // "diffuse: r g b name": the material's colour.
  for (const char* key : {"diffuse", "specular"}) {
    for (const std::string& v : e.all(key)) {
      std::istringstream in(v);
      float c[3] = {};
      std::string name;
      in >> c[0] >> c[1] >> c[2];
      std::getline(in >> std::ws, name);
      const int m = o.scene.find_material(name);
      ASSERT_GE(m, 0) << "no material named '" << name << "'";
      const Material& mat = o.scene.materials[std::size_t(m)];
      const vec4& got = std::string(key) == "diffuse" ? mat.diffuse : mat.specular;
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], c[i], 1e-6f) << key << " of " << name;
    }
  }
}

// gtest prints a failing parameter; the case name is all that helps.
void PrintTo(const Expectation& e, std::ostream* os) { *os << e.name; }

class HostileInputs : public testing::TestWithParam<Expectation> {};

TEST_P(HostileInputs, Loads) {
  const Expectation& e = GetParam();
  for (const std::string& p : e.problems) ADD_FAILURE() << e.name << ".expect: " << p;
  if (!e.problems.empty()) return;
  const Outcome o = load(case_path(e.get("load")));
  ASSERT_EQ(o.other, "") << "threw something other than rt2::Error";
  // Every line on stderr is a warning, whatever the outcome.
  std::size_t start = 0;
  for (std::size_t nl; (nl = o.err.find('\n', start)) != std::string::npos; start = nl + 1)
    EXPECT_EQ(o.err.compare(start, 9, "warning: "), 0) << "not a warning line: " << o.err;
  EXPECT_EQ(start, o.err.size()) << "stderr does not end with a newline: " << o.err;
  if (e.has("error"))
    check_error(e, o);
  else
    check_ok(e, o);
}

std::string test_name(const testing::TestParamInfo<Expectation>& info) {
  std::string s = info.param.name;
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
}

INSTANTIATE_TEST_SUITE_P(Case, HostileInputs, testing::ValuesIn(all_cases()), test_name);

// A wrong path or an empty folder must not pass as "no case failed".
TEST(HostileInputsDirectory, HasAtLeast30Cases) {
  EXPECT_GE(all_cases().size(), 30u) << "in " << hostile_dir();
}

}  // namespace
}  // namespace rt2
