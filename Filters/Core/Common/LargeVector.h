// LargeVector: a std::vector for the big work arrays (sites, planes, the nearest-site
// buffer) whose resize() leaves new elements default-initialized: no zeroing pass over
// hundreds of MB that are written in full right after. Its blocks of 2 MiB and more come
// from AllocateLarge.
//
// AllocateLarge: such blocks 2 MiB-aligned and marked MADV_HUGEPAGE, so that the kernel
// backs them with transparent huge pages where it offers them (its "madvise" mode: nothing
// process-wide is changed) and their first touch costs a fault per 2 MiB instead of one
// per 4 KiB. Where the kernel refuses, the pages stay 4 KiB. Machines differ: on one
// 2-core VM, first touching huge pages ran at 0.6-0.8 GB/s against 1.9-2.8 GB/s for 4 KiB
// pages; on another (256 MiB, one write a page), 4 KiB pages ran at 0.36 GB/s in every
// run and huge pages at 13-16 GB/s, or 0.6 GB/s while the kernel compacted memory
// (docs/benchmarks.md has the fields' times both ways).
#ifndef vtkdf_LargeVector_h
#define vtkdf_LargeVector_h

#include <cstdint>
#include <cstdlib>
#include <new>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace vtkdf
{

/// A block of `bytes` (a multiple of `alignment`, itself a multiple of 2 MiB) aligned to
/// `alignment` and marked for huge pages, to release with std::free; null when there is
/// no memory.
inline void* AllocateHuge(size_t bytes, size_t alignment)
{
  void* block = nullptr;
  if (posix_memalign(&block, alignment, bytes) != 0)
  {
    return nullptr;
  }
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  madvise(block, bytes, MADV_HUGEPAGE); // a hint: where it is refused, nothing changes
#endif
  return block;
}

/// A block of `bytes` (at least 1) to release with std::free, or null when there is no
/// memory: 2 MiB-aligned and marked for huge pages from 2 MiB on (above), malloc's below.
inline void* AllocateLarge(size_t bytes)
{
  constexpr size_t HugePage = size_t(2) << 20;
  if (bytes < HugePage)
  {
    return std::malloc(bytes > 0 ? bytes : 1);
  }
  if (bytes > SIZE_MAX - HugePage)
  {
    return nullptr;
  }
  return AllocateHuge((bytes + HugePage - 1) / HugePage * HugePage, HugePage);
}

template<typename T>
struct DefaultInitAllocator
{
  using value_type = T;

  DefaultInitAllocator() = default;
  template<typename U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept
  {
  }

  T* allocate(size_t n)
  {
    // A count whose bytes overflow size_t (an overflowing sample count) is refused as
    // std::allocator refuses it, not wrapped into a small request.
    if (n > SIZE_MAX / sizeof(T))
    {
      throw std::bad_array_new_length();
    }
    void* p = AllocateLarge(n * sizeof(T));
    if (!p)
    {
      throw std::bad_alloc();
    }
    return static_cast<T*>(p);
  }
  void deallocate(T* p, size_t) noexcept { std::free(p); }

  template<typename U, typename... Args>
  void construct(U* p, Args&&... args)
  {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template<typename U>
  void construct(U* p)
  {
    ::new (static_cast<void*>(p)) U; // default-initialization: trivial types stay as they are
  }

  template<typename U>
  bool operator==(const DefaultInitAllocator<U>&) const noexcept
  {
    return true;
  }
  template<typename U>
  bool operator!=(const DefaultInitAllocator<U>&) const noexcept
  {
    return false;
  }
};

template<typename T>
using LargeVector = std::vector<T, DefaultInitAllocator<T>>;

} // namespace vtkdf

#endif
