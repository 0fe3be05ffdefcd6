// Triangle meshes as flat buffers, ready for GL, glTF and mesh files (cf. Manifold's MeshGL).
#pragma once

#include <cstddef>
#include <cstdint>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace pdesurf {

namespace detail {
/// Blocks of at least this many bytes are mapped on their own, rounded up to whole 2 MiB,
/// 2 MiB-aligned and advised as transparent huge pages (MADV_HUGEPAGE: where THP is in
/// "madvise" mode, as on Debian), so that the first write faults in 2 MiB at a time instead
/// of 4 KiB: a 235 MB mesh takes about 120 faults instead of 58,000. Smaller blocks come from
/// operator new.
inline constexpr std::size_t kMappedBlockBytes = std::size_t{1} << 20;
/// Freed mapped blocks are kept, faulted in, for the next allocation of about their size (a
/// block is reused, cut to size, for a request of at least half its size), up to this many bytes in
/// all, the oldest unmapped first: a page fault costs 1–15 µs on a VM and the kernel clears every
/// fresh page, so a tessellation into reused pages runs without either.
inline constexpr std::size_t kBlockCacheBytes = std::size_t{1} << 30;
void* allocateMeshBlock(std::size_t bytes);
void freeMeshBlock(void* block, std::size_t bytes) noexcept;
/// Unmaps every cached block; returns the bytes released.
std::size_t releaseCachedMeshBlocks() noexcept;
/// Bytes of freed blocks held for reuse.
std::size_t cachedMeshBlockBytes() noexcept;
}  // namespace detail

/// Returns the memory of freed meshes kept for reuse (detail::kBlockCacheBytes at most) to
/// the system; the bytes released. For a long-lived process after its large meshes are gone.
inline std::size_t releaseMeshMemory() noexcept { return detail::releaseCachedMeshBlocks(); }

/// The allocator of Mesh's buffers. resize() default-initialises (leaves floats and integers
/// unwritten, as `new float[n]` does): whoever resizes a buffer writes every element, so a
/// tessellation writes each byte of its output once. Large blocks as in kMappedBlockBytes.
template <class T>
struct MeshAllocator {
  using value_type = T;
  MeshAllocator() = default;
  template <class U>
  MeshAllocator(const MeshAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) {
    // Not a pdesurf::Error: the allocator's contract (std::allocator throws this too).
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    return static_cast<T*>(detail::allocateMeshBlock(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept { detail::freeMeshBlock(p, n * sizeof(T)); }
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;  // default-initialisation: no zeroing
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  friend bool operator==(const MeshAllocator&, const MeshAllocator&) { return true; }
};

/// A mesh buffer: a std::vector whose resize() leaves new elements unwritten.
template <class T>
using MeshBuffer = std::vector<T, MeshAllocator<T>>;

/// A triangle mesh. Vertex k has position (positions[3k], positions[3k+1], positions[3k+2])
/// and unit normal likewise in `normals` (empty when the mesh has no normals). Triangle t
/// has corners indices[3t..3t+2], counter-clockwise seen from the side its normals face.
/// `patchIds[t]` names the patch (frame) triangle t came from (empty when unknown).
struct Mesh {
  MeshBuffer<float> positions;
  MeshBuffer<float> normals;
  MeshBuffer<std::uint32_t> indices;
  MeshBuffer<std::uint32_t> patchIds;

  std::size_t vertexCount() const { return positions.size() / 3; }
  std::size_t triangleCount() const { return indices.size() / 3; }
};

}  // namespace pdesurf
