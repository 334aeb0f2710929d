// rt2/kernel/kernel.h — what every file of rt2/kernel/ includes first: the instruction set
// this copy of the kernel is compiled for, and its BVH width.
//
// Everything in rt2/kernel/ is compiled once per instruction set (rt2/SConscript), with that
// set's flags and -DRT2_ISA=<sse41|avx2|avx512|scalar>, into namespace rt2::<isa>, so that
// no copy built for a wider set can stand in for another's (rt2/base/isa.h). Only
// rt2/kernel/ includes rt2/kernel/ (tests/rt2/base/layout_test.cpp checks it).
#pragma once

#if !defined(RT2_ISA)
#error "rt2/kernel/ is compiled once per instruction set: build it with -DRT2_ISA=<isa> (rt2/SConscript)"
#endif

#include "rt2/base/isa.h"

namespace rt2::RT2_ISA {

// The instruction set of this copy (its namespace is named as the enumerator).
inline constexpr Isa kIsa = Isa::RT2_ISA;
// Children per node of the triangles' wide BVH this copy walks.
inline constexpr int kWidth = bvh_width(kIsa);

}  // namespace rt2::RT2_ISA
