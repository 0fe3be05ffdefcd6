// The allocation behind Mesh's buffers (include/pdesurf/mesh.hpp: MeshAllocator calls
// allocateMeshBlock and freeMeshBlock): large blocks mapped on their own as transparent huge
// pages, kept for reuse once freed. Private to the library (src/runtime/mesh_buffer.cpp).
#pragma once

#include <cstddef>

#include "pdesurf/mesh.hpp"

namespace pdesurf::detail {

/// Blocks of at least this many bytes are mapped on their own, rounded up to whole 2 MiB,
/// 2 MiB-aligned and advised as transparent huge pages (MADV_HUGEPAGE: where THP is in
/// "madvise" mode, as on Debian), so that the first write faults in 2 MiB at a time instead
/// of 4 KiB: a 235 MB mesh takes about 120 faults instead of 58,000. Smaller blocks come from
/// operator new.
inline constexpr std::size_t kMappedBlockBytes = std::size_t{1} << 20;
/// Freed mapped blocks are kept, faulted in, for the next allocation of about their size (a
/// block is reused, cut to size, for a request of at least half its size), up to this many
/// bytes in all, the oldest unmapped first: a page fault costs 1–15 µs on a VM and the kernel
/// clears every fresh page, so a tessellation into reused pages runs without either.
inline constexpr std::size_t kBlockCacheBytes = std::size_t{1} << 30;
/// Unmaps every cached block; returns the bytes released (releaseMeshMemory).
std::size_t releaseCachedMeshBlocks() noexcept;
/// Bytes of freed blocks held for reuse.
std::size_t cachedMeshBlockBytes() noexcept;

}  // namespace pdesurf::detail
