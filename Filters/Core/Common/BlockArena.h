// BlockArena: many small arrays that live long (a sparse band's pieces: thousands of
// 36-432 KiB blocks) carved out of 8 MiB slabs that take transparent huge pages
// (MADV_HUGEPAGE, as AllocateLarge), so that their first touch costs a fault per 2 MiB
// rather than one per 4 KiB page: malloc maps each block of 128 KiB and more anew in a
// fresh process. A slab wastes at most the tail that its next block does not fit (about
// 2 % with the pieces of 32^3 bricks; 6 % with 2 MiB slabs).
//
// Each thread carves from its own slab; a slab is freed when the last of its blocks is
// released and its thread has moved on. Slabs are aligned to their size, so that a
// block finds its slab's count by masking its address; a block larger than a slab's room
// is allocated alone, at the same alignment (ReleaseBlock tells the two apart by it).
// ReleaseBlock also serves as the free function of VTK arrays that adopt the blocks.
#ifndef vtkdf_BlockArena_h
#define vtkdf_BlockArena_h

#include "Common/LargeVector.h"

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <new>

namespace vtkdf
{
namespace arena
{
constexpr size_t SlabBytes = size_t(8) << 20;
constexpr size_t HeaderBytes = 64; // the slab's count of blocks, on its own cache line

/// The blocks of a slab not yet released, plus one while its thread carves from it.
inline std::atomic<int64_t>& Blocks(char* slab)
{
  return *reinterpret_cast<std::atomic<int64_t>*>(slab);
}

inline void Unref(char* slab)
{
  if (Blocks(slab).fetch_sub(1, std::memory_order_acq_rel) == 1)
  {
    Blocks(slab).~atomic();
    std::free(slab);
  }
}

/// The calling thread's slab and how much of it is carved.
struct ThreadSlab
{
  char* Slab = nullptr;
  size_t Used = 0;
  ~ThreadSlab()
  {
    if (this->Slab)
    {
      Unref(this->Slab);
    }
  }
};
} // namespace arena

/// A block of `bytes` (64-byte aligned) to release with ReleaseBlock; throws
/// std::bad_alloc when there is no memory.
inline void* AcquireBlock(size_t bytes)
{
  using namespace arena;
  bytes = (bytes + 63) / 64 * 64;
  if (bytes > SlabBytes - HeaderBytes)
  {
    if (bytes > SIZE_MAX - SlabBytes)
    {
      throw std::bad_alloc();
    }
    void* block = AllocateHuge((bytes + SlabBytes - 1) / SlabBytes * SlabBytes, SlabBytes);
    if (!block)
    {
      throw std::bad_alloc();
    }
    return block;
  }
  thread_local ThreadSlab current;
  if (!current.Slab || current.Used + bytes > SlabBytes)
  {
    char* slab = static_cast<char*>(AllocateHuge(SlabBytes, SlabBytes));
    if (!slab)
    {
      throw std::bad_alloc();
    }
    new (slab) std::atomic<int64_t>(1);
    if (current.Slab)
    {
      Unref(current.Slab);
    }
    current.Slab = slab;
    current.Used = HeaderBytes;
  }
  char* block = current.Slab + current.Used;
  current.Used += bytes;
  Blocks(current.Slab).fetch_add(1, std::memory_order_relaxed);
  return block;
}

/// Releases a block of AcquireBlock (null: nothing).
inline void ReleaseBlock(void* block)
{
  using namespace arena;
  if (!block)
  {
    return;
  }
  const uintptr_t address = reinterpret_cast<uintptr_t>(block);
  if (address % SlabBytes == 0)
  {
    std::free(block); // a block alone
    return;
  }
  Unref(reinterpret_cast<char*>(address - address % SlabBytes));
}

/// An owning pointer to an array of AcquireBlock.
struct ReleaseBlockDeleter
{
  void operator()(void* block) const { ReleaseBlock(block); }
};
template<typename T>
using BlockArray = std::unique_ptr<T[], ReleaseBlockDeleter>;

/// An array of `count` T (trivial types: left uninitialized) from AcquireBlock.
template<typename T>
BlockArray<T> NewBlockArray(int64_t count)
{
  return BlockArray<T>(static_cast<T*>(AcquireBlock(static_cast<size_t>(count) * sizeof(T))));
}

} // namespace vtkdf

#endif
