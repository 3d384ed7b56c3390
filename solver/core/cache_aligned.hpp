#pragma once
// Arrays that threads write by rows start on a cache line (64 bytes) and
// own whole lines. With the heap's 16-byte alignment, and small objects
// packed against the arrays' ends, the 2-thread gear step spent 1.3-2x as
// long in its kick and drift and up to 1.5x in its stress pass; on one
// thread the layout made no difference (docs/speed-accuracy.md, sixth
// round).
#include <cstddef>
#include <new>
#include <vector>

namespace gearsph {

inline constexpr std::size_t kCacheLine = 64;

template <class T>
struct CacheAligned {
  using value_type = T;
  CacheAligned() = default;
  template <class U>
  constexpr CacheAligned(const CacheAligned<U>&) noexcept {}
  // Whole lines: no other object shares the first or the last line.
  static std::size_t bytes(std::size_t n) {
    return (n * sizeof(T) + kCacheLine - 1) / kCacheLine * kCacheLine;
  }
  T* allocate(std::size_t n) {
    return static_cast<T*>(::operator new (bytes(n), std::align_val_t{kCacheLine}));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    ::operator delete (p, bytes(n), std::align_val_t{kCacheLine});
  }
  template <class U>
  bool operator==(const CacheAligned<U>&) const noexcept {
    return true;
  }
};

// One quantity per particle (or per pair), cache-line aligned.
template <class T>
using Column = std::vector<T, CacheAligned<T>>;

}  // namespace gearsph
