// rt2/base/memory.h — how much memory this process may still take: the smaller of what the
// system reports available (MemAvailable, /proc/meminfo) and what its address-space limit
// (RLIMIT_AS) leaves. Loaders weigh a scene's size against it before they allocate.
#pragma once

#include <cstdint>
#include <string>

namespace rt2 {

// Memory a triangle takes from loading to tracing, at most (its mesh, its shading data, the
// binary build and the wide tree): what loaders and Accel::build weigh a scene against.
inline constexpr std::uint64_t kBytesPerTriangle = 512;
// The same for an instance (its description, its record, its box and the top tree's build).
inline constexpr std::uint64_t kBytesPerInstance = 768;

// Bytes; UINT64_MAX when neither is known.
std::uint64_t available_memory();

// "3.2 GiB", "512 MiB": a size for messages.
std::string memory_size(std::uint64_t bytes);

}  // namespace rt2
