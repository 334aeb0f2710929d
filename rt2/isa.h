// rt2/isa.h — the instruction sets rt2's ray kernels are built for, and the choice among
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
// Width: sse41 and scalar use 4-wide BVH nodes, avx2 and avx512 8-wide ones. Triangles are
// tested four at a time in every set, with the same operations in the same order, so every
// set finds the same hits, bit for bit.
#pragma once

#include <string>
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
// Children per BVH node for `isa`: 4 or 8.
constexpr int bvh_width(Isa isa) { return isa == Isa::avx2 || isa == Isa::avx512 ? 8 : 4; }

}  // namespace rt2
