// Vertex-frame models and their analytical C0 4-sided PDE patches (seed 000/001,
// Wang et al. 2022), solved by strips: docs/vertex-frames.md and docs/derivations.md §1.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "pdesurf/geometry.hpp"
#include "pdesurf/mesh.hpp"

namespace pdesurf {

// ---------------------------------------------------------------------------------------
// The model: what the user wrote (a value; io validates it, solvers assume it valid).

/// A parameter rectangle [u0,u1]×[v0,v1] inside the unit square.
struct Region {
  double u0 = 0.0, u1 = 1.0, v0 = 0.0, v1 = 1.0;
};

/// Sculpting force F = f0 sin(π(u-u0)/Lu) sin(π(v-v0)/Lv) on a region of one patch.
struct FrameForce {
  Vec3 f0 = Vec3::Zero();
  Region region;
};

/// Eight vertex indices P1..P8, counter-clockwise from (u,v) = (0,0):
/// P1 (0,0), P2 (½,0), P3 (1,0), P4 (1,½), P5 (1,1), P6 (½,1), P7 (0,1), P8 (0,½).
struct Frame {
  std::array<std::uint32_t, 8> vertices{};
  Vec3 a1 = Vec3::Ones();
  Vec3 a2 = Vec3::Ones();
  std::vector<FrameForce> forces;
};

/// A force f0 applied over the whole of each listed frame (seed Fig. 9).
struct SharedForce {
  Vec3 f0 = Vec3::Zero();
  std::vector<std::uint32_t> frames;
};

struct VertexFrameModel {
  std::string name;
  std::vector<Vec3> vertices;
  std::vector<Frame> frames;
  std::vector<SharedForce> forces;
};

// ---------------------------------------------------------------------------------------
// Topology: strips and seams, derived from shared vertex indices alone.

/// The four sides of a frame, each run with its parameter increasing:
/// Alpha = S(t,0) P1→P3, Delta = S(1,t) P3→P5, Beta = S(t,1) P7→P5, Gamma = S(0,t) P1→P7.
enum class Side : std::uint8_t { Alpha = 0, Delta = 1, Beta = 2, Gamma = 3 };

/// Local vertex slots (0-based into Frame::vertices) of a side: start, middle, end.
std::array<int, 3> sideSlots(Side side);

/// The (u, v) of parameter t along a side (t runs the side's own direction).
inline std::array<double, 2> sideParam(Side side, double t) {
  switch (side) {
    case Side::Alpha:
      return {t, 0.0};
    case Side::Delta:
      return {1.0, t};
    case Side::Beta:
      return {t, 1.0};
    default:
      return {0.0, t};
  }
}

/// 0 for the u-direction sides (Alpha, Beta: their cubic is C3), 1 for Gamma and Delta (C6).
inline int sideDirection(Side side) { return (side == Side::Alpha || side == Side::Beta) ? 0 : 1; }

/// One side of one frame.
struct FrameSide {
  std::uint32_t frame = 0;
  Side side = Side::Alpha;
};

/// A boundary curve of the model: the sides of every frame that run through the same
/// three vertices, listed in FrameTopology::edgeSides[firstSide, firstSide + sideCount).
struct ModelEdge {
  std::array<std::uint32_t, 3> vertices{};  ///< start, middle, end as its first side runs it
  std::uint32_t firstSide = 0;
  std::uint32_t sideCount = 0;
  bool collapsed() const { return vertices[0] == vertices[1] && vertices[1] == vertices[2]; }
};

/// A problem in the frame structure (found by buildTopology, reported by io).
struct TopologyError {
  enum class Kind { None, MiddleVertexDiffers } kind = Kind::None;
  FrameSide first, second;  ///< the two sides that disagree
};

struct FrameTopology {
  /// strip[k][d]: the strip of frame k in direction d (0: u, C3; 1: v, C6).
  std::vector<std::array<std::uint32_t, 2>> strip;
  /// parity[k][d] = ±1: frame k's cubic coefficient in direction d is parity × strip value.
  std::vector<std::array<std::int8_t, 2>> parity;
  std::uint32_t stripCount = 0;
  /// A pinned strip has value 0: its parities conflict (a Möbius-like loop) or it runs
  /// through an edge whose corners coincide (a pole), where only 0 keeps it a point.
  std::vector<std::uint8_t> stripPinned;
  std::vector<ModelEdge> edges;
  /// The sides of every edge, edge after edge (flat: no allocation per edge), and whether
  /// each runs its edge end→start relative to the edge's first side.
  std::vector<FrameSide> edgeSides;
  std::vector<std::uint8_t> edgeSideReversed;
  /// edgeOf[k][s]: index into `edges` of frame k's side s; sideReversed[k][s]: whether
  /// that side runs the edge end→start.
  std::vector<std::array<std::uint32_t, 4>> edgeOf;
  std::vector<std::array<std::uint8_t, 4>> sideReversed;
  /// flipped[k]: frame k is mirrored relative to the orientation chosen for its
  /// connected part (its normals and triangles are reversed so the surface is oriented).
  std::vector<std::uint8_t> flipped;
  /// False when some connected part cannot be oriented consistently (a Möbius band).
  bool orientable = true;
  TopologyError error;

  std::span<const FrameSide> sides(std::uint32_t edge) const {
    return {edgeSides.data() + edges[edge].firstSide, edges[edge].sideCount};
  }
  std::span<const std::uint8_t> reversed(std::uint32_t edge) const {
    return {edgeSideReversed.data() + edges[edge].firstSide, edges[edge].sideCount};
  }
};

/// Derives strips, edges and orientation from the frames' vertex indices. Indices must be
/// in range; an edge whose corners are shared but whose middle differs sets `error`.
FrameTopology buildTopology(const VertexFrameModel& model);

// ---------------------------------------------------------------------------------------
// Solving.

enum class Solver {
  Global,  ///< each strip value minimises the summed PDE residual of all its patches
  Local    ///< the seed's patch generation rule: breadth-first, first patch sets its strips
};

/// How a vertex-frame model is solved (the vertex-frame member of the generic SolveOptions,
/// model.hpp).
struct VertexFrameSolveOptions {
  Solver solver = Solver::Global;
  std::uint32_t seedFrame = 0;  ///< Local: where the breadth-first generation starts

  bool operator==(const VertexFrameSolveOptions&) const = default;
};

/// The particular solution of one force on one patch: S_p = k ⊙ s(u) s(v) inside the
/// region, 0 outside, with k = -f0 / (π² (a1/Lu² + a2/Lv²)) per component (docs/derivations.md
/// §1.5).
struct ForceTerm {
  Vec3 k = Vec3::Zero();
  Region region;
};

/// One analytic patch: S(u,v) = Σ c[i] m_i(u,v) + Σ force terms, with the monomials
/// m = 1, u, u², u³, v, v², v³, uv, u²v, uv² (seed eq. 4 and 13).
struct VertexFramePatch {
  std::array<Vec3, 10> c;
  std::vector<ForceTerm> forces;

  Vec3 position(double u, double v) const;
  SurfacePoint evaluate(double u, double v) const;
};

/// A solved model: one patch per frame plus the topology it was solved on.
struct VertexFrameSurface {
  std::vector<VertexFramePatch> patches;
  /// Shared, immutable: re-solving after a vertex or parameter edit reuses it.
  std::shared_ptr<const FrameTopology> topology;
  std::vector<Vec3> stripValues;  ///< per strip, per component
  /// Plain-language notes on choices the solver made (e.g. a1 = 0 leaves C3 free: 0).
  std::vector<std::string> notes;
};

/// The 8-vertex closed form of one patch (docs/derivations.md §1.2) given its two cubic
/// coefficients.
std::array<Vec3, 10> patchCoefficients(const std::array<Vec3, 8>& p, const Vec3& c3,
                                       const Vec3& c6);

/// The single-patch least-squares cubic coefficients (C3, C6) of a frame on its own,
/// per component: C3 = -(a2/(3 a1)) C9, C6 = -(a1/(3 a2)) C8 (0 where a1 or a2 is 0).
std::array<Vec3, 2> singlePatchCubics(const std::array<Vec3, 8>& p, const Vec3& a1, const Vec3& a2);

/// Solves every patch of a valid model.
VertexFrameSurface solve(const VertexFrameModel& model,
                         const VertexFrameSolveOptions& options = {});

/// Re-solves with a topology already built for the same frame structure (the studio's
/// path when only positions, a1, a2 or forces change).
VertexFrameSurface solve(const VertexFrameModel& model,
                         std::shared_ptr<const FrameTopology> topology,
                         const VertexFrameSolveOptions& options = {});

// ---------------------------------------------------------------------------------------
// Tessellation.

/// A watertight, consistently oriented triangle mesh: a point on a shared edge (or a
/// shared corner, or a collapsed edge) is one vertex; normals come from the analytic
/// derivatives, averaged over the patches that meet at shared points.
Mesh tessellate(const VertexFrameSurface& surface, const TessellateOptions& options = {});

/// The same into `out`, reusing its buffers' capacity (no allocation when the sizes repeat).
void tessellate(const VertexFrameSurface& surface, const TessellateOptions& options, Mesh& out);

/// Tessellates a surface again and again, as an editor does while a vertex is dragged. The
/// vertex layout, the triangles and the patch ids depend only on the topology and the
/// resolution, so while those stay the same (the same `surface.topology` object, as
/// `solve(model, topology)` keeps it, and the same resolution) a call rewrites only the
/// positions and normals. Every call's mesh is bit-identical to `tessellate(surface, options)`.
/// Not thread-safe: one Tessellator per thread.
class Tessellator {
 public:
  Tessellator();
  ~Tessellator();
  Tessellator(Tessellator&&) noexcept;
  Tessellator& operator=(Tessellator&&) noexcept;

  /// The mesh of `surface`; the reference stays valid (and the mesh unchanged) until the next
  /// call. Throws InvalidArgument as tessellate() does.
  const Mesh& tessellate(const VertexFrameSurface& surface, const TessellateOptions& options = {});

  /// The mesh of the last call.
  const Mesh& mesh() const { return mesh_; }

  /// Changes whenever a call lays the mesh out afresh: while it stays the same, the indices,
  /// patch ids and vertex count of mesh() stay the same (only positions and normals change).
  std::uint64_t layoutVersion() const { return layoutVersion_; }

 private:
  struct Cache;  // the layout, the topology it was made for, and scratch buffers
  std::unique_ptr<Cache> cache_;
  Mesh mesh_;
  std::uint64_t layoutVersion_ = 0;
};

}  // namespace pdesurf
