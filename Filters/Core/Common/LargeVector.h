// LargeVector: a std::vector for the big work arrays (sites, planes, the nearest-site
// buffer) whose resize() leaves new elements default-initialized: no zeroing pass over
// hundreds of MB that are written in full right after.
//
// The blocks are not marked MADV_HUGEPAGE. That was tried: on the 2-core VMs this
// project is measured on, first touching a huge-page block ran at 0.6-0.8 GB/s against
// 1.9-2.8 GB/s for 4 KiB pages (54 MB, two threads), and vtkdf linfac on dragon_871k
// at 128^3 took 2.44 s against 2.12 s (median of 4 alternating runs each).
#ifndef vtkdf_LargeVector_h
#define vtkdf_LargeVector_h

#include <cstdint>
#include <cstdlib>
#include <new>
#include <utility>
#include <vector>

namespace vtkdf
{

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
    void* p = std::malloc(n > 0 ? n * sizeof(T) : 1);
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
