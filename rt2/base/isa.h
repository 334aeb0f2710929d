// rt2/base/isa.h — the instruction sets rt2's kernel is built for, and the choice among them
// at run time.
//
// One binary runs on any x86-64 CPU with SSE4.1. rt2/kernel/ is compiled once per set, each
// copy in its own namespace (rt2::sse41, rt2::avx2, rt2::avx512) with that set's flags, and
// nothing else gets them, so nothing that runs before the choice can hold a wider
// instruction (tests/rt2/base/isa_test.cpp disassembles rt2cpr to check). The choice is made
// once, from CPUID: the widest set the CPU runs, unless `--isa` forces one. Every set finds
// the same hits, bit for bit. The scalar build (scons arch=scalar) has one set, `scalar`.
#pragma once

#include <string>
#include <type_traits>
#include <vector>

namespace rt2 {

enum class Isa { scalar, sse41, avx2, avx512 };

// The sets this build contains, narrowest first.
const std::vector<Isa>& built_isas();
// Whether this CPU can run `isa` (and the build contains it).
bool isa_supported(Isa isa);
// The widest built set this CPU runs.
Isa best_isa();
// "sse41", "avx2", "avx512", "scalar".
const char* isa_name(Isa isa);
// Parses a name as isa_name gives it; throws rt2::Error for an unknown name, one this
// build lacks, or one this CPU cannot run.
Isa parse_isa(const std::string& name);
// Children per BVH node for `isa`: 4, 8 or 16 (one SIMD register of child boxes).
constexpr int bvh_width(Isa isa) {
  return isa == Isa::avx512 ? 16 : isa == Isa::avx2 ? 8 : 4;
}
// f(std::integral_constant<int, W>{}) for W = bvh_width(isa): code over the tree of the width
// `isa` traces, chosen once (Accel's trees, their statistics, cluster visibility).
template <class F>
decltype(auto) with_bvh_width(Isa isa, F&& f) {
  switch (bvh_width(isa)) {
    case 16: return f(std::integral_constant<int, 16>{});
    case 8: return f(std::integral_constant<int, 8>{});
    default: return f(std::integral_constant<int, 4>{});
  }
}

}  // namespace rt2
