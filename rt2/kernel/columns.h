// rt2/kernel/columns.h — a batch of records as structure of arrays: C columns of 32-bit
// values (floats, or unsigned integers through u()), each 64-byte aligned and followed by
// kSlack values of slack, so that a SIMD pass of up to 16 lanes may load whole vectors from
// any index below size(), and store them at size() after reserve(size() + 16).
//
// The render kernel's batches are kept this way: the packet queries load a packet's rays with
// one vector load per coordinate, and the shading lanes append rays a vector at a time.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>

#include "rt2/kernel/kernel.h"

namespace rt2::RT2_ISA {

template <int C>
class Columns {
 public:
  static constexpr std::size_t kSlack = 16;

  Columns() = default;
  // A moved-from batch is empty (and can be used again).
  Columns(Columns&& o) noexcept { swap(o); }
  Columns& operator=(Columns&& o) noexcept {
    swap(o);
    return *this;
  }
  void swap(Columns& o) noexcept {
    data_.swap(o.data_);
    const std::size_t size = size_, capacity = capacity_, stride = stride_;
    size_ = o.size_, capacity_ = o.capacity_, stride_ = o.stride_;
    o.size_ = size, o.capacity_ = capacity, o.stride_ = stride;
  }

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  void clear() { size_ = 0; }

  // Room for n records (the storage only grows; the values are kept).
  void reserve(std::size_t n) {
    if (n > capacity_) grow(n);
  }
  // Adds n records, their values unset; returns the index of the first.
  std::size_t extend(std::size_t n) {
    reserve(size_ + n);
    const std::size_t first = size_;
    size_ += n;
    return first;
  }

  float* f(int c) { return data_.get() + std::size_t(c) * stride_; }
  const float* f(int c) const { return data_.get() + std::size_t(c) * stride_; }
  // A column of unsigned integers (scalar code reads and writes it as such; SIMD passes move
  // its bits through float vectors, as the scalar build's compress does through floats).
  std::uint32_t* u(int c) { return reinterpret_cast<std::uint32_t*>(f(c)); }
  const std::uint32_t* u(int c) const { return reinterpret_cast<const std::uint32_t*>(f(c)); }

 private:
  void grow(std::size_t n) {
    std::size_t capacity = std::max(n, std::max<std::size_t>(2 * capacity_, 256));
    capacity = (capacity + 15) / 16 * 16;  // whole 64-byte lines per column
    const std::size_t stride = capacity + kSlack;
    const std::size_t bytes = std::size_t(C) * stride * sizeof(float);
    Storage data(static_cast<float*>(std::aligned_alloc(64, bytes)));
    if (!data) throw std::bad_alloc();
    std::memset(data.get(), 0, bytes);  // the slack too: loads past size() read zeros at first
    for (int c = 0; c < C && size_ > 0; ++c)
      std::memcpy(data.get() + std::size_t(c) * stride, f(c), size_ * sizeof(float));
    data_ = std::move(data);
    capacity_ = capacity;
    stride_ = stride;
  }
  struct Free {
    void operator()(float* p) const { std::free(p); }
  };
  using Storage = std::unique_ptr<float[], Free>;
  Storage data_;
  std::size_t size_ = 0, capacity_ = 0, stride_ = 0;
};

}  // namespace rt2::RT2_ISA
