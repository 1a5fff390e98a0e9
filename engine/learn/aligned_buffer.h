#pragma once

// Buffers aligned to 64 bytes (a cache line, one AVX-512 register), so that kernel loads of
// plane and row starts do not straddle cache lines.

#include <cstddef>
#include <new>
#include <vector>

namespace recon::learn {

template <typename T>
struct CacheAlignedAllocator {
  using value_type = T;
  static constexpr std::align_val_t kAlignment{64};

  CacheAlignedAllocator() = default;
  template <typename U>
  CacheAlignedAllocator(const CacheAlignedAllocator<U>&) {}  // NOLINT: allocator rebind

  T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kAlignment)); }
  void deallocate(T* p, std::size_t) { ::operator delete(p, kAlignment); }

  template <typename U>
  bool operator==(const CacheAlignedAllocator<U>&) const {
    return true;
  }
};

/// A float vector whose data starts on a 64-byte boundary.
using AlignedFloats = std::vector<float, CacheAlignedAllocator<float>>;

}  // namespace recon::learn
