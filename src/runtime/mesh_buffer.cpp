// Mesh buffers: large blocks mapped on their own and advised as transparent huge pages
// (include/pdesurf/mesh.hpp says why).
#include <cstdint>
#include <new>

#include "pdesurf/mesh.hpp"

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
}  // namespace

void* allocateMeshBlock(std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (bytes >= kHugeBlockBytes) {
    // Map a huge page more than needed, then unmap the ends so the block starts on a huge
    // page boundary: only aligned 2 MiB ranges can be backed by huge pages.
    const std::size_t size = mappedBytes(bytes);
    void* raw =
        mmap(nullptr, size + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (raw == MAP_FAILED) throw std::bad_alloc();
    const auto start = reinterpret_cast<std::uintptr_t>(raw);
    const std::uintptr_t aligned = (start + kHugePage - 1) / kHugePage * kHugePage;
    if (aligned > start) munmap(raw, aligned - start);
    if (const std::size_t tail = start + size + kHugePage - (aligned + size); tail > 0)
      munmap(reinterpret_cast<void*>(aligned + size), tail);
    void* block = reinterpret_cast<void*>(aligned);
    madvise(block, size, MADV_HUGEPAGE);  // a hint: without THP the block stays in 4 KiB pages
    return block;
  }
#endif
  return ::operator new(bytes);
}

void freeMeshBlock(void* block, std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (bytes >= kHugeBlockBytes) {
    munmap(block, mappedBytes(bytes));
    return;
  }
#endif
  ::operator delete(block);
}

}  // namespace pdesurf::detail
