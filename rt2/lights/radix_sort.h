// rt2/lights/radix_sort.h — a stable, parallel LSD radix sort of (key, value) pairs of 32-bit
// unsigned integers: the sort of a light BVH's Morton codes (rt2/lights/morton.h), rebuilt every
// frame for up to 10^6 lights.
#pragma once

#include <cstdint>
#include <vector>

namespace rt2 {

// Sorts the pairs (keys[i], values[i]) by key, ascending and stable: pairs with equal keys
// keep their input order. Only the low `key_bits` bits of a key (1 ... 32) are compared;
// pairs that differ only above them also keep their input order. Morton codes take
// key_bits = 30.
//
// Least-significant digit first, in ceil(key_bits / 8) passes of 8 bits (30 bits: 4
// passes); a pass in which every key has the same digit is skipped, as it would only copy.
// Each pass runs on `threads` OpenMP threads (<= 0: all hardware threads): each thread
// counts the digits of its own contiguous chunk, a prefix sum over (digit, thread) gives
// each thread where its keys of each digit go, and each thread then scatters its chunk in
// order, which keeps the sort stable. Inputs under 4096 pairs sort on one thread, and every
// thread gets at least 1024 pairs. Called inside a parallel region, it gets the threads
// that OpenMP nesting allows (by default one). The result is the same whatever the thread
// count.
//
// Memory: two scratch arrays of the input's size, kept per calling thread (thread_local)
// and never shrunk, so a call every frame allocates nothing once they have grown; they hold
// 8 bytes per pair of the largest sort made on that thread until the thread exits. When the
// sorted pairs end up in the scratch arrays (an odd number of passes ran), the vectors'
// buffers are exchanged with them rather than copied back: sizes and contents are as
// expected, but pointers and iterators into keys or values taken before the call no longer
// point into them.
//
// Throws std::invalid_argument if keys.size() != values.size() or key_bits is not in
// 1 ... 32 (then nothing is modified).
void radix_sort_pairs(std::vector<std::uint32_t>& keys, std::vector<std::uint32_t>& values,
                      int threads, int key_bits = 32);

}  // namespace rt2
