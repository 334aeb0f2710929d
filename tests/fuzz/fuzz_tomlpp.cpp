// tests/fuzz/fuzz_tomlpp.cpp — libFuzzer target for toml++ alone: toml::parse on the input,
// without rt2's screening (rt2/io/toml_scene.cpp, TomlScreen).
//
// Not for campaigns: it finds the toml++ 3.3 bugs that rt2 works around, again and again. It
// exists to minimise (scripts/fuzz --target tomlpp --minimize CRASH) an input that crashed
// fuzz_scene inside toml++ once rt2 screens it out, so that the smallest input that breaks
// toml++ is known and kept as a hostile case (tests/hostile/).
#include <toml++/toml.h>

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)toml::parse(std::string_view(reinterpret_cast<const char*>(data), size));
  } catch (const toml::parse_error&) {
    // the expected failure
  }
  return 0;
}
