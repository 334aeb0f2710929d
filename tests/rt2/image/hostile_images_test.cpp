// The image files of tests/hostile/images/ as a scene's texture or environment: each case is
// compiled (CompiledScene::compile, as rt2cpr does after loading) and must end as its
// <case>.expect says, one test per case (Case/HostileImages.Compile/<case>).
//
// The contract checked: a refusal is an rt2::Error of one line that starts with the image's
// path and contains the expected text; nothing else escapes, nothing crashes, hangs or
// leaks (the asan build), and nothing is printed on stderr (OpenImageIO's and the format
// libraries' complaints are silenced). An image that is read gives finite lookups. The
// .expect format is in tests/hostile/images/README.md; generate.py there writes the cases.
#include <gtest/gtest.h>
#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#endif

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "rt2/base/error.h"
#include "rt2/render/compiled_scene.h"

#ifndef RT2_SOURCE_DIR
#error "the build defines RT2_SOURCE_DIR as the repository root"
#endif

namespace rt2 {
namespace {

namespace fs = std::filesystem;

const fs::path& cases_dir() {
  static const fs::path dir = fs::path(RT2_SOURCE_DIR) / "tests/hostile/images";
  return dir;
}

struct Expectation {
  std::string name;
  std::map<std::string, std::string> keys;
  std::vector<std::string> problems;  // in the .expect file itself

  bool has(const std::string& k) const { return keys.count(k) > 0; }
  std::string get(const std::string& k) const { return has(k) ? keys.at(k) : std::string(); }
};

const std::vector<std::string> kKnownKeys = {"texture", "environment", "error", "ok",
                                             "max_pixels"};

std::string trim(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return {};
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

Expectation parse_expect(const fs::path& path) {
  Expectation e;
  e.name = path.stem().string();
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    const std::size_t colon = t.find(':');
    const std::string key = trim(t.substr(0, std::min(colon, t.size())));
    if (colon == std::string::npos ||
        std::find(kKnownKeys.begin(), kKnownKeys.end(), key) == kKnownKeys.end() || e.has(key)) {
      e.problems.push_back("bad or repeated line: " + t);
      continue;
    }
    e.keys[key] = trim(t.substr(colon + 1));
  }
  if (e.has("texture") == e.has("environment"))
    e.problems.push_back("needs exactly one of texture: and environment:");
  if (e.has("error") == e.has("ok")) e.problems.push_back("needs exactly one of error: and ok:");
  return e;
}

std::vector<Expectation> all_cases() {
  std::vector<Expectation> cases;
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(cases_dir(), ec))
    if (entry.path().extension() == ".expect") cases.push_back(parse_expect(entry.path()));
  std::sort(cases.begin(), cases.end(),
            [](const Expectation& a, const Expectation& b) { return a.name < b.name; });
  return cases;
}

// The image a case names: relative to tests/hostile/images/, or absolute.
std::string image_path(const Expectation& e) {
  const std::string name = e.get(e.has("texture") ? "texture" : "environment");
  return fs::path(name).is_absolute() ? name : (cases_dir() / name).string();
}

void PrintTo(const Expectation& e, std::ostream* os) { *os << e.name; }

// Allocations made while one exists are not reported as leaks (the asan build): OpenImageIO
// 2.4's PNG reader leaks a copy of its error message when libpng gives up inside a file.
struct LeakCheckOff {
#if defined(__SANITIZE_ADDRESS__)
  LeakCheckOff() { __lsan_disable(); }
  ~LeakCheckOff() { __lsan_enable(); }
#endif
};

class HostileImages : public testing::TestWithParam<Expectation> {};

TEST_P(HostileImages, Compile) {
  const Expectation& e = GetParam();
  for (const std::string& p : e.problems) ADD_FAILURE() << e.name << ".expect: " << p;
  if (!e.problems.empty()) return;
  const std::string path = image_path(e);
  Scene scene;
  if (e.has("texture"))
    scene.textures.push_back(TextureDesc{path, {}, true});
  else
    scene.environment = EnvironmentDesc{.image = path};
  if (e.has("max_pixels")) scene.assets.max_image_pixels = std::stoull(e.get("max_pixels"));
  std::string error, other;
  testing::internal::CaptureStderr();
  try {
    [[maybe_unused]] const LeakCheckOff oiio_leaks;
    const CompiledScene c = CompiledScene::compile(scene, BvhConfig{});
    for (const vec4& d : {vec4(0, 1, 0), vec4(0.6f, 0, 0.8f), vec4(0, -1, 0)}) {
      const vec4 v = e.has("texture") ? c.textures.sample(0, d[0], d[2], 0.1f)
                                      : c.environment.radiance(d) + c.environment.irradiance(d);
      for (int k = 0; k < 3; ++k) EXPECT_TRUE(std::isfinite(v[k])) << "lookup " << k;
    }
  } catch (const Error& x) {
    error = x.what();
  } catch (const std::exception& x) {
    other = std::string("std::exception: ") + x.what();
  } catch (...) {
    other = "an exception that is not a std::exception";
  }
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  ASSERT_EQ(other, "");
  if (e.has("ok")) {
    EXPECT_EQ(error, "") << "expected to compile";
    return;
  }
  ASSERT_NE(error, "") << "compiled, but expected an error containing: " << e.get("error");
  EXPECT_EQ(error.find_first_of("\r\n"), std::string::npos) << "not one line: " << error;
  EXPECT_EQ(error.rfind(path + ": ", 0), 0u) << "expected to start with '" << path << ": ': " << error;
  EXPECT_NE(error.find(e.get("error")), std::string::npos)
      << "expected '" << e.get("error") << "' in: " << error;
}

std::string test_name(const testing::TestParamInfo<Expectation>& info) {
  std::string s = info.param.name;
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
}

INSTANTIATE_TEST_SUITE_P(Case, HostileImages, testing::ValuesIn(all_cases()), test_name);

// A wrong path or an empty folder must not pass as "no case failed".
TEST(HostileImagesDirectory, HasAtLeast60Cases) {
  EXPECT_GE(all_cases().size(), 60u) << "in " << cases_dir();
}

}  // namespace
}  // namespace rt2
