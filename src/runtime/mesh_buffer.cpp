// Mesh buffers: large blocks mapped on their own, advised as transparent huge pages, and
// kept for reuse once freed (src/runtime/mesh_buffer.hpp says why).
#include <algorithm>
#include <cstdint>
#include <mutex>
#include <new>
#include <utility>
#include <vector>

#include "runtime/mesh_buffer.hpp"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace pdesurf::detail {

namespace {
/// The size of a transparent huge page on x86-64 and arm64 (with 4 KiB base pages).
constexpr std::size_t kHugePage = std::size_t{2} << 20;

std::size_t mappedBytes(std::size_t bytes) {
  return (bytes + kHugePage - 1) / kHugePage * kHugePage;
}

#if defined(__linux__) && defined(MADV_HUGEPAGE)
#define PDESURF_MAPS_MESH_BLOCKS 1

/// Freed large blocks, already faulted in, waiting to be handed out again (most recent
/// last). Guarded by `mutex`; allocations of this size are rare (a few per tessellation).
struct BlockCache {
  struct Block {
    void* address;
    std::size_t mapped;
  };
  std::mutex mutex;
  std::vector<Block> blocks;
  std::size_t bytes = 0;
};

/// Never destroyed: meshes freed by other static destructors still return their blocks.
BlockCache& blockCache() {
  static BlockCache* cache = new BlockCache;
  return *cache;
}

void* mapBlock(std::size_t size) {
  // Map a huge page more than needed, then unmap the ends so the block starts on a huge
  // page boundary: only aligned 2 MiB ranges can be backed by huge pages.
  void* raw =
      mmap(nullptr, size + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();  // Not a pdesurf::Error: out of memory.
  const auto start = reinterpret_cast<std::uintptr_t>(raw);
  const std::uintptr_t aligned = (start + kHugePage - 1) / kHugePage * kHugePage;
  if (aligned > start) munmap(raw, aligned - start);
  if (const std::size_t tail = start + size + kHugePage - (aligned + size); tail > 0)
    munmap(reinterpret_cast<void*>(aligned + size), tail);
  void* block = reinterpret_cast<void*>(aligned);
  madvise(block, size, MADV_HUGEPAGE);  // a hint: without THP the block stays in 4 KiB pages
  return block;
}

/// A cached block for `size` mapped bytes: the smallest cached block of at least `size`
/// and at most twice that (so a small buffer does not pin a large block), its tail beyond
/// `size` unmapped (both are whole huge pages, so the block keeps its huge pages); nullptr
/// when there is none.
void* takeCachedBlock(std::size_t size) {
  BlockCache::Block taken{nullptr, 0};
  {
    BlockCache& cache = blockCache();
    const std::lock_guard lock(cache.mutex);
    auto best = cache.blocks.end();
    for (auto it = cache.blocks.begin(); it != cache.blocks.end(); ++it)
      if (it->mapped >= size && it->mapped <= 2 * size &&
          (best == cache.blocks.end() || it->mapped < best->mapped))
        best = it;
    if (best == cache.blocks.end()) return nullptr;
    taken = *best;
    cache.bytes -= best->mapped;
    cache.blocks.erase(best);
  }
  if (taken.mapped > size) munmap(static_cast<char*>(taken.address) + size, taken.mapped - size);
  return taken.address;
}
#endif
}  // namespace

void* allocateMeshBlock(std::size_t bytes) {
#if PDESURF_MAPS_MESH_BLOCKS
  {
    if (bytes >= kMappedBlockBytes) {
      const std::size_t size = mappedBytes(bytes);
      if (void* cached = takeCachedBlock(size)) return cached;
      return mapBlock(size);
    }
  }
#endif
  return ::operator new(bytes);
}

void freeMeshBlock(void* block, std::size_t bytes) noexcept {
#if PDESURF_MAPS_MESH_BLOCKS
  {
    if (bytes >= kMappedBlockBytes) {
      const std::size_t size = mappedBytes(bytes);
      BlockCache& cache = blockCache();
      const std::lock_guard lock(cache.mutex);
      if (size <= kBlockCacheBytes) {
        // Oldest first out, until the block fits under the cap.
        std::size_t drop = 0;
        for (; cache.bytes + size > kBlockCacheBytes; ++drop) {
          munmap(cache.blocks[drop].address, cache.blocks[drop].mapped);
          cache.bytes -= cache.blocks[drop].mapped;
        }
        cache.blocks.erase(cache.blocks.begin(), cache.blocks.begin() + drop);
        try {
          cache.blocks.push_back({block, size});
          cache.bytes += size;
          return;
        } catch (...) {  // no room to remember it: unmapped below
        }
      }
      munmap(block, size);
      return;
    }
  }
#endif
  ::operator delete(block);
}

std::size_t releaseCachedMeshBlocks() noexcept {
#if PDESURF_MAPS_MESH_BLOCKS
  BlockCache& cache = blockCache();
  const std::lock_guard lock(cache.mutex);
  for (const BlockCache::Block& b : cache.blocks) munmap(b.address, b.mapped);
  cache.blocks.clear();
  return std::exchange(cache.bytes, 0);
#else
  return 0;
#endif
}

std::size_t cachedMeshBlockBytes() noexcept {
#if PDESURF_MAPS_MESH_BLOCKS
  BlockCache& cache = blockCache();
  const std::lock_guard lock(cache.mutex);
  return cache.bytes;
#else
  return 0;
#endif
}

}  // namespace pdesurf::detail

namespace pdesurf {

std::size_t releaseMeshMemory() noexcept { return detail::releaseCachedMeshBlocks(); }

}  // namespace pdesurf
