// rt2/base/isa.h — the instruction sets rt2's ray kernels are built for, and the choice among
// them at run time.
//
// One binary runs on any x86-64 CPU with SSE4.1. The code that traces rays (the wide BVH
// traversal, the triangle tests, the render kernel) is compiled once per instruction set,
// each copy in its own namespace (rt2::sse41, rt2::avx2, rt2::avx512; see isa_namespace.h),
// and only those translation units get -mavx2 / -mavx512*: nothing that runs before the
// choice can contain a wider instruction (a test disassembles the program to check). The
// choice is made once, from CPUID: the widest set the CPU supports, unless `--isa` forces
// one. The scalar build (scons arch=scalar) has a single set, `scalar`.
//
// Width: sse41 and scalar use 4-wide BVH nodes, avx2 8-wide ones and avx512 16-wide ones:
// a node's child boxes fill one SIMD register per plane. Against 8-wide nodes on AVX-512, a
// random line through the mesh meets 27-28 % fewer inner nodes (wide_sah), and bench_trace
// (rt2's ratio to Embree, the two binaries alternated, four rounds, one thread, the four
// bench-peer meshes) ran incoherent rays 3-13 % faster with the fast triangle test and
// 5-14 % with the watertight one, shadow rays 4-9 % (watertight -2 ... +13 %),
// reflections 5-8 % (0-11 %), primary rays -5 ... +3 % (-3 ... +5 %).
// Triangles are tested four at a time in every set (eight, two blocks, where the 8- and
// 16-wide walks pair them), with the same operations in the same order, so every set finds
// the same hits, bit for bit.
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
