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
/// The allocation behind MeshAllocator (src/runtime/mesh_buffer.hpp: large blocks mapped as
/// huge pages and kept for reuse once freed).
void* allocateMeshBlock(std::size_t bytes);
void freeMeshBlock(void* block, std::size_t bytes) noexcept;
}  // namespace detail

/// Returns the memory of freed meshes kept for reuse (up to 1 GiB of large blocks) to the
/// system; the bytes released. For a long-lived process after its large meshes are gone.
std::size_t releaseMeshMemory() noexcept;

/// The allocator of Mesh's buffers. resize() default-initialises (leaves floats and integers
/// unwritten, as `new float[n]` does): whoever resizes a buffer writes every element, so a
/// tessellation writes each byte of its output once. Blocks of 1 MiB or more are mapped as
/// huge pages and kept for reuse once freed (releaseMeshMemory).
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
