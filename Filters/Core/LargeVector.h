// LargeVector: a std::vector for the big work arrays (sites, planes, the nearest-site
// buffer), with two differences that matter when they reach hundreds of MB:
// - resize() leaves new elements default-initialized (no zeroing pass), for arrays that
//   are written in full right after;
// - on Linux, blocks of 8 MiB and more are 2 MiB aligned and marked MADV_HUGEPAGE, so
//   that touching them first costs a few hundred page faults, not a few hundred thousand
//   (with transparent huge pages set to "madvise", Debian's default).
#ifndef vtkdf_LargeVector_h
#define vtkdf_LargeVector_h

#include <cstdlib>
#include <new>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace vtkdf
{

template<typename T>
struct HugePageAllocator
{
  using value_type = T;
  static constexpr size_t HugePage = size_t(2) << 20;

  HugePageAllocator() = default;
  template<typename U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept
  {
  }

  T* allocate(size_t n)
  {
    const size_t bytes = n * sizeof(T);
    void* p = nullptr;
#if defined(__linux__)
    if (bytes >= 4 * HugePage)
    {
      const size_t rounded = (bytes + HugePage - 1) / HugePage * HugePage;
      p = std::aligned_alloc(HugePage, rounded);
      if (p)
      {
        madvise(p, rounded, MADV_HUGEPAGE); // advice only: failure changes nothing
      }
    }
#endif
    if (!p)
    {
      p = std::malloc(bytes > 0 ? bytes : 1);
    }
    if (!p)
    {
      throw std::bad_alloc();
    }
    return static_cast<T*>(p);
  }
  void deallocate(T* p, size_t) noexcept
  {
    std::free(p);
  }

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
  bool operator==(const HugePageAllocator<U>&) const noexcept
  {
    return true;
  }
  template<typename U>
  bool operator!=(const HugePageAllocator<U>&) const noexcept
  {
    return false;
  }
};

template<typename T>
using LargeVector = std::vector<T, HugePageAllocator<T>>;

} // namespace vtkdf

#endif
