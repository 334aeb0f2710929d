// Zero cost, proven on the compiler's output: the reflect formula i - 2 n dot(n, i),
// compiled with the release flags (tests/SConscript makes reflect_probe.s), contains no
// call and at most 6 SSE arithmetic / shuffle instructions (the thesis got 5: mulps, dpps,
// shufps, mulps, subps; the broadcast dot product needs no shufps).
#include <gtest/gtest.h>

#include <fstream>
#include <set>
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

// SSE/AVX arithmetic and shuffle mnemonics (moves and loads are not counted).
bool is_sse_arith_or_shuffle(std::string m) {
  static const std::set<std::string> packed = {"add", "sub", "mul", "div", "min", "max", "sqrt",
                                               "rcp", "rsqrt", "and", "andn", "or", "xor",
                                               "hadd", "hsub"};
  static const std::set<std::string> shuffles = {
      "dpps", "shufps", "pshufd", "unpcklps", "unpckhps", "movhlps", "movlhps", "blendps",
      "blendvps", "insertps", "broadcastss", "permilps"};
  if (m.size() > 1 && m[0] == 'v') m.erase(0, 1);  // AVX encodings
  if (shuffles.count(m)) return true;
  if (m.rfind("fmadd", 0) == 0 || m.rfind("fmsub", 0) == 0 || m.rfind("fnmadd", 0) == 0 ||
      m.rfind("fnmsub", 0) == 0)
    return true;
  if (m.size() > 2 && (m.ends_with("ps") || m.ends_with("ss")))
    return packed.count(m.substr(0, m.size() - 2)) > 0;
  return false;
}

void check_probe(const std::string& name) {
#if defined(MLIB_SCALAR)
  // Decided at compile time: the probe of a scalar build has no SSE sequence to count.
  GTEST_SKIP() << "scalar build (MLIB_SCALAR): the probe is plain lane-by-lane code, so the "
                  "SSE instruction budget does not apply";
#endif
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
