// rt2/base/isa.cpp — which instruction sets are built and which this CPU runs.
#include "rt2/base/isa.h"

#include "rt2/base/error.h"

namespace rt2 {

const std::vector<Isa>& built_isas() {
#if defined(MLIB_SCALAR)
  static const std::vector<Isa> isas{Isa::scalar};
#else
  static const std::vector<Isa> isas{Isa::sse41, Isa::avx2, Isa::avx512};
#endif
  return isas;
}

bool isa_supported(Isa isa) {
  bool built = false;
  for (Isa b : built_isas()) built |= b == isa;
  if (!built) return false;
  __builtin_cpu_init();
  switch (isa) {
    case Isa::scalar: return true;
    case Isa::sse41: return __builtin_cpu_supports("sse4.1");
    case Isa::avx2:
      return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
             __builtin_cpu_supports("bmi2");
    case Isa::avx512:
      return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
             __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512cd") &&
             __builtin_cpu_supports("avx2") && __builtin_cpu_supports("bmi2");
  }
  return false;
}

Isa best_isa() {
  Isa best = built_isas().front();
  for (Isa isa : built_isas())
    if (isa_supported(isa)) best = isa;
  return best;
}

const char* isa_name(Isa isa) {
  switch (isa) {
    case Isa::scalar: return "scalar";
    case Isa::sse41: return "sse41";
    case Isa::avx2: return "avx2";
    case Isa::avx512: return "avx512";
  }
  return "?";
}

Isa parse_isa(const std::string& name) {
  std::string known;
  for (Isa isa : built_isas()) {
    known += (known.empty() ? "" : ", ") + std::string(isa_name(isa));
    if (name != isa_name(isa)) continue;
    if (!isa_supported(isa)) throw Error("this CPU cannot run ISA '" + name + "'");
    return isa;
  }
  throw Error("unknown ISA '" + name + "' (this build has " + known + ")");
}

}  // namespace rt2
