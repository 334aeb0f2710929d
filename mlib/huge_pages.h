// mlib/huge_pages.h — an allocator for large arrays read at random (a BVH's nodes and
// leaves): memory backed by 2 MiB pages where the operating system offers them.
//
// A ray's walk reads a few nodes and leaves anywhere in its tree. Once the tree is much
// larger than the TLB covers in 4 KiB pages (a few thousand entries: some megabytes), most
// of those reads first walk the page table; with 2 MiB pages a hundred megabytes of tree
// needs fifty entries. Linux backs an anonymous mapping with transparent huge pages when
// the program asks with madvise(MADV_HUGEPAGE), which Debian's default policy ("madvise")
// requires; Embree does the same for its trees. Without THP the memory is only aligned.
// Arrays below one huge page take ordinary pages (allocate_small).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

#if !defined(__SANITIZE_ADDRESS__)
#include <tbb/scalable_allocator.h>
#endif

namespace mlib {

inline constexpr std::size_t kHugePageBytes = std::size_t(2) << 20;

// Whether an allocation of `bytes` is placed on huge pages (allocate_huge) or not.
inline bool wants_huge_pages(std::size_t bytes) { return bytes >= kHugePageBytes; }

// `bytes` (> 0) of memory aligned to kHugePageBytes, its length rounded up to whole huge
// pages, advised to the kernel as huge-page memory. Freed with std::free. Throws
// std::bad_alloc when there is no memory.
inline void* allocate_huge(std::size_t bytes) {
  if (bytes > PTRDIFF_MAX - kHugePageBytes) throw std::bad_alloc();  // no object is larger
  const std::size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
  void* p = std::aligned_alloc(kHugePageBytes, rounded);
  if (!p) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  madvise(p, rounded, MADV_HUGEPAGE);  // advice: a kernel without THP ignores it (EINVAL)
#endif
  return p;
}

// `bytes` (> 0) aligned to `align`, below one huge page (ordinary pages, so small trees
// take no more memory than their size). From oneTBB's scalable allocator rather than the C
// library: glibc hands a freed block of a few hundred kilobytes back to the system, and the
// next build takes every page of it again as a fresh one (a fault and a page of zeros
// each), while tbbmalloc keeps freed blocks for the next request, which matters to a tree
// rebuilt over and over. In a sanitized build from operator new, which AddressSanitizer
// watches. Freed with free_small(p, align).
#if defined(__SANITIZE_ADDRESS__)
inline void* allocate_small(std::size_t bytes, std::size_t align) {
  return ::operator new(bytes, std::align_val_t{align});
}
inline void free_small(void* p, std::size_t align) noexcept {
  ::operator delete(p, std::align_val_t{align});
}
#else
inline void* allocate_small(std::size_t bytes, std::size_t align) {
  void* p = scalable_aligned_malloc(bytes, align);
  if (!p) throw std::bad_alloc();
  return p;
}
inline void free_small(void* p, std::size_t) noexcept { scalable_aligned_free(p); }
#endif

template <class T>
struct HugePageAllocator {
  using value_type = T;

  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    const std::size_t bytes = n * sizeof(T);
    if (wants_huge_pages(bytes)) return static_cast<T*>(allocate_huge(bytes));
    return static_cast<T*>(allocate_small(bytes, alignof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (wants_huge_pages(n * sizeof(T)))
      std::free(p);
    else
      free_small(p, alignof(T));
  }

  template <class U>
  bool operator==(const HugePageAllocator<U>&) const noexcept {
    return true;
  }
};

// A std::vector whose storage, once it reaches a huge page, lies on huge pages.
template <class T>
using HugePageVector = std::vector<T, HugePageAllocator<T>>;

// HugePageAllocator whose containers leave the elements they add without a value
// (resize(n), vector(n)) unwritten when their type is trivially copyable and trivially
// destructible, for the code that fills them: so a page of a large array is first touched by
// the thread that writes it, not zeroed by one thread before. Other types are default-
// initialized.
template <class T>
struct UninitializedHugePageAllocator : HugePageAllocator<T> {
  UninitializedHugePageAllocator() = default;
  template <class U>
  UninitializedHugePageAllocator(const UninitializedHugePageAllocator<U>&) noexcept {}

  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    if constexpr (!(std::is_trivially_copyable_v<U> && std::is_trivially_destructible_v<U>))
      ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

// A HugePageVector whose resize leaves the new elements of a trivially copyable type unwritten.
template <class T>
using HugePageBuffer = std::vector<T, UninitializedHugePageAllocator<T>>;

}  // namespace mlib
