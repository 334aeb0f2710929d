// Zero cost, proven on the compiler's output: the reflect formula i - 2 n dot(n, i),
// compiled with the release flags (tests/SConscript makes reflect_probe.s), contains no
// call and at most 6 SSE arithmetic / shuffle instructions (the thesis got 5: mulps, dpps,
// shufps, mulps, subps; the broadcast dot product needs no shufps).
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace {

// The instruction lines of function `name` in a GNU assembler listing.
std::vector<std::string> function_body(const std::string& path, const std::string& name) {
  std::ifstream in(path);
  EXPECT_TRUE(in) << "cannot read " << path;
  std::vector<std::string> body;
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    if (!inside) {
      inside = line == name + ":";
      continue;
    }
    if (line.rfind("\t.size\t" + name, 0) == 0 || line.rfind(".LFE", 0) == 0) break;
    if (line.empty() || line[0] != '\t' || line[1] == '.') continue;  // labels, directives
    body.push_back(line.substr(1));
  }
  return body;
}

std::string mnemonic(const std::string& insn) { return insn.substr(0, insn.find('\t')); }

bool is_sse_arith_or_shuffle(const std::string& m) {
  static const std::regex re(
      "v?(add|sub|mul|div|min|max|sqrt|rcp|rsqrt|and|andn|or|xor|hadd|hsub)(ps|ss)|"
      "v?dpps|v?shufps|v?pshufd|v?unpck[lh]ps|v?movhlps|v?movlhps|v?blendv?ps|v?insertps|"
      "vbroadcastss|vpermilps|vfn?m(add|sub)[0-9]+(ps|ss)");
  return std::regex_match(m, re);
}

void check_probe(const std::string& name) {
  const auto body = function_body(RT2_REFLECT_ASM, name);
  ASSERT_FALSE(body.empty()) << name << " not found in " << RT2_REFLECT_ASM;
  int sse = 0;
  std::ostringstream listing;
  for (const auto& insn : body) {
    const std::string m = mnemonic(insn);
    listing << "  " << insn << "\n";
    EXPECT_NE(m.rfind("call", 0), 0u) << name << " calls: " << insn;
    EXPECT_NE(m.rfind("jmp", 0), 0u) << name << " jumps (tail call?): " << insn;
    sse += is_sse_arith_or_shuffle(m);
  }
  EXPECT_LE(sse, 6) << name << ":\n" << listing.str();
  EXPECT_GE(sse, 3) << "suspiciously few instructions (is the probe computing?):\n"
                    << listing.str();
  ::testing::Test::RecordProperty(name + "_sse_instructions", sse);
  std::printf("%s: %d SSE arithmetic/shuffle instructions\n%s", name.c_str(), sse,
              listing.str().c_str());
}

TEST(Asm, ReflectWithRegisterOperandsHasNoCallAndAtMostSixSseInstructions) {
  check_probe("reflect_probe_regs");
}

TEST(Asm, ReflectWithReferenceOperandsHasNoCallAndAtMostSixSseInstructions) {
  check_probe("reflect_probe_refs");
}

}  // namespace
