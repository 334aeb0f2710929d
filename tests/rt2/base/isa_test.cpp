// Instruction sets: the choice at run time, and the rule that makes one binary safe on any
// SSE4.1 CPU — no instruction wider than the baseline outside the translation units built
// for AVX2 and AVX-512 (their code lives in rt2::avx2 and rt2::avx512).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <regex.h>
#include <string>
#include <vector>

#include "rt2/base/error.h"
#include "rt2/base/isa.h"
#include "rt2/render/kernel_table.h"
#include "rt2/render/trace_kernels.h"
#include "tests/rt2/test_util.h"

namespace rt2 {
namespace {

TEST(Isa, TheBestIsTheWidestTheCpuRunsAndNamesRoundTrip) {
  const Isa best = best_isa();
  EXPECT_TRUE(isa_supported(best));
  for (Isa isa : built_isas()) {
    EXPECT_EQ(render_kernels(isa).isa, isa);
    EXPECT_EQ(trace_kernels(isa).isa, isa);
    if (!isa_supported(isa)) continue;
    EXPECT_LE(static_cast<int>(isa), static_cast<int>(best));
    EXPECT_EQ(parse_isa(isa_name(isa)), isa);
  }
  EXPECT_THROW(parse_isa("avx9000"), Error);
  EXPECT_THROW(parse_isa(""), Error);
  EXPECT_EQ(bvh_width(Isa::sse41), 4);
  EXPECT_EQ(bvh_width(Isa::avx2), 8);
  EXPECT_EQ(bvh_width(Isa::avx512), 16);
}

// Every function of the rt2cpr program whose disassembly uses an AVX instruction (a VEX or
// EVEX mnemonic, or a ymm / zmm / mask register) must belong to rt2::avx2 or rt2::avx512.
// An inline function compiled into a wide unit but defined outside those namespaces would
// be merged by the linker with the baseline copy, and whichever copy won would then run on
// CPUs that lack the instructions.
TEST(Isa, NoWideInstructionLeaksOutOfTheWideTranslationUnits) {
#if defined(__AVX2__) || defined(MLIB_SCALAR)
  GTEST_SKIP() << "this build's baseline is not SSE4.1 (scons arch=avx2, native or scalar)";
#endif
  const std::string cmd = std::string("objdump -d --no-show-raw-insn -C ") + RT2CPR_BIN;
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(::popen(cmd.c_str(), "r"), ::pclose);
  ASSERT_TRUE(pipe) << cmd;
  // POSIX extended expressions: std::regex is slow on a whole disassembly, and GCC 12 warns
  // about its internals under the sanitizers.
  regex_t function_line, wide_instruction;
  ASSERT_EQ(::regcomp(&function_line, "^[0-9a-f]+ <(.*)>:$", REG_EXTENDED), 0);
  ASSERT_EQ(::regcomp(&wide_instruction,
                      "\t(v[a-z0-9]+ |v[a-z0-9]+$|k[a-z]+ .*%k[0-7]|.*%[yz]mm)",
                      REG_EXTENDED | REG_NOSUB),
            0);
  std::string function, line;
  std::size_t wide_in_isa_units = 0;
  std::vector<std::string> leaks;
  char buf[4096];
  bool leaked_here = false;
  while (std::fgets(buf, sizeof buf, pipe.get())) {
    line.assign(buf);
    if (!line.empty() && line.back() == '\n') line.pop_back();
    regmatch_t m[2];
    if (::regexec(&function_line, line.c_str(), 2, m, 0) == 0) {
      function = line.substr(m[1].rm_so, m[1].rm_eo - m[1].rm_so);
      leaked_here = false;
      continue;
    }
    if (::regexec(&wide_instruction, line.c_str(), 0, nullptr, 0) != 0) continue;
    if (function.find("rt2::avx2::") != std::string::npos ||
        function.find("rt2::avx512::") != std::string::npos) {
      ++wide_in_isa_units;
    } else if (!leaked_here) {
      leaked_here = true;
      leaks.push_back(function + ": " + line);
    }
  }
  ::regfree(&function_line);
  ::regfree(&wide_instruction);
  EXPECT_TRUE(leaks.empty()) << leaks.size() << " functions, first: " << leaks.front();
  if (std::find(built_isas().begin(), built_isas().end(), Isa::avx2) != built_isas().end()) {
    EXPECT_GT(wide_in_isa_units, 1000u);  // the check does see the wide code
  }
}

}  // namespace
}  // namespace rt2
