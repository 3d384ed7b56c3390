#pragma once
// Arrays that threads write by rows start on a cache line (64 bytes) and
// own whole lines, so that two threads never write one line (false
// sharing; docs/speed-accuracy-history.md, "arrays on their own cache lines").
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstring>
#include <new>
#include <vector>

namespace gearsph {

inline constexpr std::size_t kCacheLine = 64;

// Arrays of kMapFrom or more are mapped on their own, page-aligned (the
// executable fixes glibc's mmap threshold there: apps/gearsph/main.cpp);
// from the heap, arrays of 64 KiB and more are as likely to share a page
// offset. Every such array would start at the same offset in a page, so the i-th
// entries of the arrays one loop reads would fall in one set of the L1 and
// L2 caches and evict each other: a 1e5-particle plate's step took 1.65x
// as long. Each starts instead at its own multiple of a cache line past
// the page, in a rotating order, at most 1/16 of its size further and at
// most 64 KiB (the L2's set period here is 128 KiB).
inline constexpr std::size_t kStaggerFrom = std::size_t{64} << 10;
inline constexpr std::size_t kMapFrom = std::size_t{1} << 20;
inline std::size_t stagger(std::size_t bytes) {
  static std::atomic<std::size_t> count{0};
  const std::size_t lines = std::min<std::size_t>(1024, bytes / 16 / kCacheLine);
  // 41 is odd: successive arrays take different L1 sets.
  return kCacheLine * (1 + (count.fetch_add(1, std::memory_order_relaxed) * 41) % lines);
}

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
    const std::size_t b = bytes(n);
    if (b < kStaggerFrom) {
      return static_cast<T*>(::operator new (b, std::align_val_t{kCacheLine}));
    }
    // The shift is kept in the word before the array.
    const std::size_t shift = stagger(b);
    char* raw = static_cast<char*>(::operator new (b + shift, std::align_val_t{kCacheLine}));
    char* out = raw + shift;
    std::memcpy(out - sizeof shift, &shift, sizeof shift);
    return reinterpret_cast<T*>(out);
  }
  void deallocate(T* p, std::size_t n) noexcept {
    const std::size_t b = bytes(n);
    if (b < kStaggerFrom) {
      ::operator delete (p, b, std::align_val_t{kCacheLine});
      return;
    }
    char* out = reinterpret_cast<char*>(p);
    std::size_t shift;
    std::memcpy(&shift, out - sizeof shift, sizeof shift);
    ::operator delete (out - shift, b + shift, std::align_val_t{kCacheLine});
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
