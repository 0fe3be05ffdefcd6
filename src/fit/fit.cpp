// Fitting a vertex-frame model to a mesh: closest points both ways (CGAL AABB trees), a
// sparse linear least-squares step in the vertex positions with the strips' cubic
// coefficients tied to them exactly, and a line search on the measured RMS (docs/rebuild.md).
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "fit/linear_surface.hpp"
#include "numerics/force_shape.hpp"
#include "numerics/triangle_tree.hpp"
#include "pdesurf/rebuild.hpp"

namespace pdesurf {

double FitMeasure::rms() const {
  return std::sqrt(0.5 * (rmsToMesh * rmsToMesh + rmsToModel * rmsToModel));
}

namespace {

using fit::LinearSurface;
using fit::PointWeights;

using detail::Point;
using detail::toPoint;
using detail::toVec;
using detail::Tree;
using detail::Triangle;
using detail::Triangles;

/// Below this RMS relative to the diagonal the fit is exact to rounding (float meshes
/// carry 6e-8 relative): nothing is left to lower.
constexpr double kExactRms = 1e-14;

/// Gauss–Newton steps that move a mesh vertex's foot point from the sample triangle's
/// estimate onto the patch: the estimate is within a sample cell, so a few suffice.
constexpr int kProjectionSteps = 4;

/// A foot point whose barycentric coordinate opposite a boundary edge is below this lies on
/// the boundary: its pair counts the whole distance, not the normal part alone.
constexpr double kOnBoundary = 1e-9;

/// A foot point whose smallest barycentric coordinate is below this lies on an edge or a
/// corner of its triangle (where the distance's direction, not the triangle's normal, is
/// the pair's normal); a sample nearer than this (relative to the diagonal) keeps the
/// triangle's normal.
constexpr double kOnEdge = 1e-9;

/// The tangential weight adapts as a trust region does: divided by 10 after a full step,
/// multiplied by 10 (up to 1, plain distances) after a shortened one, never below this
/// (the smoothness term keeps the system well posed down there).
constexpr double kMinTangentialWeight = 1e-6;

/// Halvings of a step tried before the tangential weight rises (below plain distances;
/// at plain distances FitOptions::maxHalvings): measured on the mannequin devil's 32 × 32
/// grid, a step that failed whole and halved then failed at every further halving too.
constexpr std::uint32_t kHalvingsBeforeDamping = 1;

/// Full steps in a row (none raising the weight) before the tangential weight is lowered.
constexpr std::uint32_t kCleanStepsToLower = 2;

/// The barycentric coordinates of p (in the triangle's plane) in triangle a b c.
Eigen::Vector3d barycentric(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const double total = n.squaredNorm();
  if (!(total > 0.0)) return {1.0, 0.0, 0.0};
  const double lb = (p - a).cross(c - a).dot(n) / total;
  const double lc = (b - a).cross(p - a).dot(n) / total;
  return {1.0 - lb - lc, lb, lc};
}

/// The target mesh: its triangles with area in an AABB tree, its vertices as samples.
struct Target {
  Triangles triangles;
  std::vector<Vec3> normals;  ///< unit normal per triangle
  /// Per triangle, bit k: its edge opposite corner k is on the mesh's boundary.
  std::vector<std::uint8_t> boundary;
  Tree tree;
  std::vector<Vec3> samples;    ///< the vertices that triangles with area use
  std::vector<double> weights;  ///< a third of the area of their triangles, summing to 1
  double diagonal = 0.0;

  explicit Target(const Mesh& mesh) {
    auto vertex = [&](std::uint32_t v) { return detail::meshVertex(mesh, v); };
    std::vector<double> area(mesh.vertexCount(), 0.0);
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    double total = 0.0;
    // Edges of one triangle with area are the boundary.
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edgeUse;
    std::vector<std::size_t> kept;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
      const std::uint32_t* i = &mesh.indices[3 * t];
      const Vec3 a = vertex(i[0]), b = vertex(i[1]), c = vertex(i[2]);
      if (!((b - a).cross(c - a).norm() > 0.0)) continue;
      kept.push_back(t);
      for (int k = 0; k < 3; ++k) ++edgeUse[std::minmax(i[(k + 1) % 3], i[(k + 2) % 3])];
    }
    for (std::size_t t : kept) {
      const std::uint32_t* i = &mesh.indices[3 * t];
      const Vec3 a = vertex(i[0]), b = vertex(i[1]), c = vertex(i[2]);
      const double at = 0.5 * (b - a).cross(c - a).norm();
      std::uint8_t bits = 0;
      for (int k = 0; k < 3; ++k)
        if (edgeUse[std::minmax(i[(k + 1) % 3], i[(k + 2) % 3])] == 1) bits |= 1u << k;
      boundary.push_back(bits);
      triangles.emplace_back(toPoint(a), toPoint(b), toPoint(c));
      normals.push_back((b - a).cross(c - a).normalized());
      for (int k = 0; k < 3; ++k) {
        area[i[k]] += at / 3.0;
        lo = lo.cwiseMin(vertex(i[k]));
        hi = hi.cwiseMax(vertex(i[k]));
      }
      total += at;
    }
    if (triangles.empty())
      throw std::invalid_argument(
          fmt::format("the mesh has no triangle with area ({} triangles)", mesh.triangleCount()));
    for (std::uint32_t v = 0; v < mesh.vertexCount(); ++v)
      if (area[v] > 0.0) {
        samples.push_back(vertex(v));
        weights.push_back(area[v] / total);
      }
    diagonal = (hi - lo).norm();
    tree.insert(triangles.cbegin(), triangles.cend());
    tree.build();
    tree.accelerate_distance_queries();
  }
};

/// A closest-point pair: the surface point S(frame, u, v) should be at `target`.
/// The squared distance counted is (S - target)ᵀ M (S - target) with
/// M = n nᵀ + tangentialWeight (I - n nᵀ): along the normal n in full, along the tangent
/// plane a little.
struct Pair {
  std::uint32_t frame = 0;
  double u = 0.0, v = 0.0;
  Vec3 target = Vec3::Zero();
  Vec3 normal = Vec3::Zero();  ///< unit, or zero where none is known (then M = I)
  double weight = 0.0;
  std::int64_t sample = -1;  ///< the surface sample (weights precomputed), or -1: a mesh vertex's
};

/// The pairs at one surface and the distances they measure.
struct Evaluation {
  std::vector<Pair> pairs;
  FitMeasure measure;
  std::vector<std::uint32_t> foldsPerFrame;  ///< folded surface samples per frame
  /// Per surface sample, the mesh triangle its closest point is on; per mesh vertex, the
  /// cell of the surface's sample grid its closest point is on: the next evaluation's
  /// hints (a query that starts from a near point prunes the tree at once).
  std::vector<std::uint32_t> meshTriangle, surfaceCell;
};

/// The automatic sample count: about as many surface samples as mesh vertices (the two
/// directions then weigh alike in the work), from a 4 × 4 grid a patch (enough to see its
/// cubic along each side) to the 9 × 9 that small layouts always had.
constexpr std::uint32_t kMinAutoSamples = 4, kMaxAutoSamples = 9;

/// The reduced normal equations are solved by conjugate gradients, preconditioned by the
/// sparse Cholesky factor of their local part, until the residual is this small relative to
/// the right-hand side (far below the float mesh's rounding, 6e-8, in the positions) ...
constexpr double kCgTolerance = 1e-13;
/// ... or until the residual at the current unknowns has fallen by this factor: the step
/// need not be more exact than the next linearisation (an inexact Gauss–Newton step), and
/// near the answer the residual is itself small, so the bound tightens as the fit converges
/// (the mannequin devil's 32 × 32 grid: half the CG steps, the same final RMS).
constexpr double kCgReduction = 1e-4;
/// At most this many CG steps a solve (the preconditioner leaves the strips' coupling
/// only: a few dozen steps in practice); then the best iterate is used.
constexpr int kMaxCgSteps = 400;

/// Preconditioned conjugate gradients on A x = b from x (apply: v ↦ A v, A symmetric;
/// precondition: r ↦ M⁻¹ r), until the residual is within `tolerance` of |b| or within
/// `reduction` of the starting residual, kMaxCgSteps at most; a direction of non-positive
/// curvature (A not positive there, or rounding) ends it.
template <class Apply, class Precondition>
Eigen::VectorXd conjugateGradients(const Apply& apply, const Precondition& precondition,
                                   const Eigen::VectorXd& b, Eigen::VectorXd x, double tolerance,
                                   double reduction) {
  Eigen::VectorXd r = b - apply(x);
  Eigen::VectorXd z = precondition(r);
  Eigen::VectorXd p = z;
  double rz = r.dot(z);
  const double bound = std::max(tolerance * b.norm(), reduction * r.norm());
  for (int step = 0; step < kMaxCgSteps && r.norm() > bound; ++step) {
    const Eigen::VectorXd hp = apply(p);
    const double curvature = p.dot(hp);
    if (!(curvature > 0.0)) break;
    const double alpha = rz / curvature;
    x += alpha * p;
    r -= alpha * hp;
    z = precondition(r);
    const double next = r.dot(z);
    p = z + (next / rz) * p;
    rz = next;
  }
  return x;
}

/// A step may fold over up to this share of the samples even where the surface had fewer
/// folded ones: at a cliff or near the mesh's boundary a sample's closest point can lie on
/// a triangle that faces away, which is no fold of the surface, and holding every such
/// sample would stall the fit (three_peaks.off: RMS 1.3 % instead of 0.16 %).
constexpr double kFoldAllowance = 0.005;

/// Where a step would fold more samples of some frames over, those frames' vertices stay
/// and the rest of the step is tried again, at most this many times a step.
constexpr int kMaxFoldRetries = 4;

constexpr double kPi = std::numbers::pi;

/// The a1, a2 step of the shape fit (parameterStep): Levenberg–Marquardt damping λ, relative
/// to the diagonal of the Gauss–Newton matrix, starting here, divided by 10 after a whole
/// step and multiplied by 10 after a halved or failed one, within these bounds ...
constexpr double kStartParameterDamping = 1e-2;
constexpr double kMinParameterDamping = 1e-6;
constexpr double kMaxParameterDamping = 1e6;
/// ... plus this fraction of the largest diagonal entry everywhere: parameters that move no
/// strip value (a frame's a1 and a2 scaled together on strips of one frame, a strip value
/// pinned to 0) then stay, and the system is positive definite.
constexpr double kParameterFloor = 1e-9;
/// Its conjugate gradients stop when the residual is this small relative to the gradient:
/// the step need not be more exact than its linearisation.
constexpr double kParameterCgTolerance = 1e-6;
/// No ln a1 or ln a2 changes by more than this in one step (a factor e).
constexpr double kMaxLogStep = 1.0;
/// Halvings of the a1, a2 step tried before it is given up for this iteration.
constexpr std::uint32_t kParameterHalvings = 3;

std::uint32_t automaticSamples(std::size_t meshSamples, std::size_t frames) {
  const double perFrame = static_cast<double>(meshSamples) / static_cast<double>(frames);
  const auto g = static_cast<std::uint32_t>(std::ceil(std::sqrt(perFrame))) + 1;
  return std::clamp(g, kMinAutoSamples, kMaxAutoSamples);
}

class Fitter {
 public:
  Fitter(const VertexFrameModel& start, const Mesh& target, const FitOptions& options)
      : model_(start), target_(target), options_(options) {
    const std::uint32_t g = options.samplesPerSide != 0
                                ? options.samplesPerSide
                                : automaticSamples(target_.samples.size(), start.frames.size());
    samplesPerSide_ = g;
    for (std::uint32_t j = 0; j < g; ++j)
      for (std::uint32_t i = 0; i < g; ++i) {
        // Trapezoid weights: a border sample stands for half a cell, a corner for a quarter.
        const double wu = (i == 0 || i + 1 == g) ? 0.5 : 1.0;
        const double wv = (j == 0 || j + 1 == g) ? 0.5 : 1.0;
        grid_.push_back(
            {static_cast<double>(i) / (g - 1), static_cast<double>(j) / (g - 1), wu * wv});
      }
    buildLaplacian();
    tangentialWeight_ = options.tangentialWeight;
    rebuildLinear();
  }

  FitResult run() {
    FitResult result;
    Evaluation current = evaluate(model_);
    report(result, {0, current.measure, 0.0});
    std::uint32_t iteration = 1;
    result.stopReason = iterate(result, current, iteration);
    if (options_.fitShape && current.measure.rms() > kExactRms) {
      enableShape();
      const std::string shapeReason = iterate(result, current, iteration);
      result.stopReason = fmt::format("vertices: {}; vertices, forces, a1 and a2: {}",
                                      result.stopReason, shapeReason);
    }
    result.model = model_;
    return result;
  }

 private:
  /// Iterations from `current` (numbered from `iteration` on, at most maxIterations of them)
  /// until they converge or no step lowers the RMS; returns why they stopped. In the shape
  /// phase each iteration is a least-squares step in the vertices and forces, then a step in
  /// a1 and a2 (parameterStep), either of which may fail alone.
  std::string iterate(FitResult& result, Evaluation& current, std::uint32_t& iteration) {
    std::uint32_t cleanSteps = kCleanStepsToLower - 1;  // the first full step lowers it
    for (std::uint32_t count = 1;; ++count) {
      const double rms = current.measure.rms();
      if (rms <= kExactRms) return "the surface lies on the mesh to rounding";
      if (count > options_.maxIterations)
        return fmt::format("reached the iteration limit ({})", options_.maxIterations);
      // Line search: the whole step, else halves of it, until the RMS does not increase (and
      // no more samples fold over: tryStep holds back the frames that would fold); when no
      // fraction lowers the RMS, the tangential weight rises (towards plain distances) and
      // the least squares is solved again.
      double step = 1.0;
      bool accepted = false, raised = false;
      for (;;) {
        const Eigen::VectorXd y0 = state();
        const Eigen::VectorXd solution = leastSquares(current.pairs, y0);
        // Below plain distances a step that fails whole and halved says the tangential
        // weight is too small: raising it (a better damped solution) costs one solve, the
        // further halvings an evaluation each and rarely succeed.
        const std::uint32_t halvings = tangentialWeight_ >= 1.0
                                           ? options_.maxHalvings
                                           : std::min(options_.maxHalvings, kHalvingsBeforeDamping);
        for (std::uint32_t h = 0; h <= halvings && !accepted; ++h) {
          step = std::ldexp(1.0, -static_cast<int>(h));
          auto tried = tryStep(y0, y0 + step * (solution - y0), current);
          if (!tried) continue;
          auto& [candidate, next] = *tried;
          if (next.measure.rms() > rms) continue;
          if (options_.preventFolds && next.measure.foldedSamples > foldLimit(current)) continue;
          model_ = std::move(candidate);
          current = std::move(next);
          accepted = true;
        }
        if (accepted || tangentialWeight_ >= 1.0) break;
        tangentialWeight_ = std::min(1.0, 10.0 * tangentialWeight_);
        raised = true;
      }
      const double parameterFraction = shape_ ? parameterStep(current) : 0.0;
      if (!accepted && parameterFraction == 0.0)
        return fmt::format(
            "no step along the least-squares solution lowers the RMS (tried down to 1/{}){}",
            1u << options_.maxHalvings, shape_ ? ", nor any step in a1 and a2" : "");
      if (!accepted) step = 0.0;
      // Full steps in a row lower the tangential weight; a shortened step, or one that needed
      // the weight raised, starts the count again (a weight that just failed would fail
      // again at once, and each failure costs a solve).
      cleanSteps = step < 1.0 || raised ? 0 : cleanSteps + 1;
      if (step < 1.0) {
        tangentialWeight_ = std::min(1.0, 10.0 * tangentialWeight_);
      } else if (cleanSteps >= kCleanStepsToLower) {
        tangentialWeight_ = std::max(kMinTangentialWeight, 0.1 * tangentialWeight_);
        cleanSteps = 0;
      }
      report(result, {iteration++, current.measure, step, shape_, parameterFraction});
      const double decrease = (rms - current.measure.rms()) / rms;
      // A shortened step says the linearisation was poor, not that the fit is done: the
      // tangential weight has risen, so the next step is better damped. Only a full step (or
      // one at plain distances, which cannot be damped more) that gains little ends the fit.
      if (decrease < options_.tolerance && (step == 1.0 || tangentialWeight_ >= 1.0))
        return fmt::format(
            "converged: the last iteration lowered the RMS by {:.3g}%, less than the tolerance "
            "{:.3g}%",
            100.0 * decrease, 100.0 * options_.tolerance);
    }
  }

  struct GridPoint {
    double u, v, weight;
  };

  void report(FitResult& result, const FitIteration& iteration) const {
    result.iterations.push_back(iteration);
    if (options_.onIteration) options_.onIteration(iteration);
  }

  /// The linear map for the current a1, a2 and fixed forces, and what depends on it: the
  /// surface samples' weights and the strips' rows on the unknowns. In the shape phase the
  /// forces are unknowns, not an offset: the map is built without them.
  void rebuildLinear() {
    if (shape_) {
      VertexFrameModel bare = model_;
      for (Frame& f : bare.frames) f.forces.clear();
      linear_ = std::make_unique<LinearSurface>(bare);
    } else {
      linear_ = std::make_unique<LinearSurface>(model_);
    }
    const std::size_t nFrames = model_.frames.size();
    gridWeights_.resize(nFrames * grid_.size());
    for (std::uint32_t k = 0; k < nFrames; ++k)
      for (std::size_t s = 0; s < grid_.size(); ++s)
        gridWeights_[k * grid_.size() + s] = linear_->weights(k, grid_[s].u, grid_[s].v);
    std::vector<Eigen::Triplet<double>> t;
    for (int c = 0; c < 3; ++c) {
      const auto& rows = linear_->stripRows(c);
      for (Eigen::Index s = 0; s < rows.outerSize(); ++s)
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows, s); it; ++it)
          t.emplace_back(3 * s + c, 3 * it.col() + c, it.value());
    }
    // The forces' unknowns (shape phase) follow the vertices' and no strip depends on them.
    strips_.resize(3 * static_cast<Eigen::Index>(linear_->stripCount()), unknownCount());
    strips_.setFromTriplets(t.begin(), t.end());
  }

  /// 3 per vertex, and in the shape phase 3 per frame (its force's amplitude).
  Eigen::Index unknownCount() const {
    return 3 *
           static_cast<Eigen::Index>(model_.vertices.size() + (shape_ ? model_.frames.size() : 0));
  }

  /// The unknowns that the least squares moves: the vertex positions, flattened, then in the
  /// shape phase each frame's force amplitude.
  Eigen::VectorXd state() const {
    Eigen::VectorXd y(unknownCount());
    const std::size_t n = model_.vertices.size();
    for (std::size_t j = 0; j < n; ++j)
      y.segment<3>(3 * static_cast<Eigen::Index>(j)) = model_.vertices[j];
    if (shape_)
      for (std::size_t k = 0; k < model_.frames.size(); ++k)
        y.segment<3>(3 * static_cast<Eigen::Index>(n + k)) = forceAmplitude(model_.frames[k]);
    return y;
  }

  /// The current model with the unknowns set to y.
  VertexFrameModel modelAt(const Eigen::VectorXd& y) const {
    VertexFrameModel m = model_;
    const std::size_t n = m.vertices.size();
    for (std::size_t j = 0; j < n; ++j)
      m.vertices[j] = y.segment<3>(3 * static_cast<Eigen::Index>(j));
    if (shape_)
      for (std::size_t k = 0; k < m.frames.size(); ++k)
        setForceAmplitude(m.frames[k], y.segment<3>(3 * static_cast<Eigen::Index>(n + k)));
    return m;
  }

  /// The amplitude of a frame's whole-frame force: its particular solution is
  /// k sin(πu) sin(πv) with k = -f0 / (π² (a1 + a2)) (docs/derivations.md §1.5, Lu = Lv = 1),
  /// computed as the solver computes it (forceTerm, src/vertex_frames/solve.cpp).
  static Vec3 forceAmplitude(const Frame& f) {
    if (f.forces.empty()) return Vec3::Zero();
    Vec3 k = Vec3::Zero();
    for (int c = 0; c < 3; ++c)
      if (f.forces[0].f0[c] != 0.0) k[c] = -f.forces[0].f0[c] / (kPi * kPi * (f.a1[c] + f.a2[c]));
    return k;
  }

  /// Sets the frame's whole-frame force to amplitude k for its a1, a2 (none where k is 0).
  static void setForceAmplitude(Frame& f, const Vec3& k) {
    f.forces.clear();
    if (k == Vec3::Zero()) return;
    const Vec3 f0 = -kPi * kPi * k.cwiseProduct(f.a1 + f.a2);
    f.forces.push_back({f0, Region{}});
  }

  /// The shape phase: the forces join the unknowns (their f0 from now on follows a1 and
  /// a2 so that the amplitude stays when those change).
  void enableShape() {
    shape_ = true;
    rebuildLinear();
  }

  /// One damped Gauss–Newton step in ln a1 and ln a2 of every frame (per component) on the
  /// pairs of `current`, with the vertices and forces' amplitudes fixed; taken whole, else
  /// halved, only where the measured RMS falls. Returns the fraction taken (0: none).
  ///
  /// a1 and a2 move the surface only through the strip values X (the forces keep their
  /// amplitude), so S_i = S_i⁰ + A_i ΔX and ΔX ≈ G Δθ with G = linear_->parameterJacobian.
  /// The squared distances are then ½ Δθᵀ (Gᵀ K G) Δθ + (Gᵀ g)ᵀ Δθ + const with
  /// K = Σ w A_iᵀ M A_i and g = Σ w A_iᵀ M (S_i⁰ - t_i), both over the strips (small and
  /// sparse); Gᵀ K G couples every frame of two crossing strips, so it is never formed:
  /// Jacobi-preconditioned conjugate gradients apply it as products with G, K and Gᵀ.
  /// Levenberg–Marquardt damping λ diag(GᵀKG) adapts as the tangential weight does.
  double parameterStep(Evaluation& current) {
    const FrameTopology& topo = linear_->topology();
    const auto nFrames = static_cast<std::uint32_t>(model_.frames.size());
    const auto strips3 = 3 * static_cast<Eigen::Index>(topo.stripCount);
    const Eigen::Index params = 6 * static_cast<Eigen::Index>(nFrames);
    if (strips3 == 0) return 0.0;
    const VertexFrameSurface surface = solve(model_, linear_->sharedTopology());
    const Eigen::SparseMatrix<double> g = linear_->parameterJacobian(model_.vertices);
    using Block = Eigen::Matrix<double, 6, 6>;
    std::vector<Block> blocks(nFrames, Block::Zero());
    Eigen::VectorXd gradientX = Eigen::VectorXd::Zero(strips3);
    const double mu = tangentialWeight_;
    for (const Pair& p : current.pairs) {
      const double b0 = topo.parity[p.frame][0] * fit::cubicShape(p.u);
      const double b1 = topo.parity[p.frame][1] * fit::cubicShape(p.v);
      const Eigen::Matrix3d m =
          mu * Eigen::Matrix3d::Identity() + (1.0 - mu) * p.normal * p.normal.transpose();
      const Vec3 mr = m * (surface.patches[p.frame].position(p.u, p.v) - p.target);
      Block& block = blocks[p.frame];
      block.block<3, 3>(0, 0) += (p.weight * b0 * b0) * m;
      block.block<3, 3>(0, 3) += (p.weight * b0 * b1) * m;
      block.block<3, 3>(3, 0) += (p.weight * b1 * b0) * m;
      block.block<3, 3>(3, 3) += (p.weight * b1 * b1) * m;
      gradientX.segment<3>(3 * Eigen::Index{topo.strip[p.frame][0]}) += p.weight * b0 * mr;
      gradientX.segment<3>(3 * Eigen::Index{topo.strip[p.frame][1]}) += p.weight * b1 * mr;
    }
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(std::size_t{nFrames} * 36);
    for (std::uint32_t k = 0; k < nFrames; ++k)
      for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j)
          triplets.emplace_back(3 * Eigen::Index{topo.strip[k][i / 3]} + i % 3,
                                3 * Eigen::Index{topo.strip[k][j / 3]} + j % 3, blocks[k](i, j));
    Eigen::SparseMatrix<double> kx(strips3, strips3);
    kx.setFromTriplets(triplets.begin(), triplets.end());
    // diag(GᵀKG): a parameter moves at most its frame's two strips (two entries a column).
    Eigen::VectorXd diagonal = Eigen::VectorXd::Zero(params);
    for (Eigen::Index col = 0; col < g.outerSize(); ++col)
      for (Eigen::SparseMatrix<double>::InnerIterator a(g, col); a; ++a)
        for (Eigen::SparseMatrix<double>::InnerIterator b(g, col); b; ++b)
          diagonal[col] += a.value() * kx.coeff(a.row(), b.row()) * b.value();
    const double largest = diagonal.maxCoeff();
    if (!(largest > 0.0)) return 0.0;
    const Eigen::VectorXd damped =
        (1.0 + parameterDamping_) * diagonal.array() + kParameterFloor * largest;
    const Eigen::VectorXd rhs = -(g.transpose() * gradientX);
    auto apply = [&](const Eigen::VectorXd& x) {
      const Eigen::VectorXd gx = g * x;
      return Eigen::VectorXd(g.transpose() * (kx * gx) +
                             parameterDamping_ * diagonal.cwiseProduct(x) +
                             kParameterFloor * largest * x);
    };
    Eigen::VectorXd delta = conjugateGradients(
        apply, [&](const Eigen::VectorXd& r) { return Eigen::VectorXd(r.cwiseQuotient(damped)); },
        rhs, Eigen::VectorXd::Zero(params), kParameterCgTolerance, 0.0);
    // A trust region: no parameter changes by more than a factor e in one step.
    const double largestChange = delta.cwiseAbs().maxCoeff();
    if (!(largestChange > 0.0) || !std::isfinite(largestChange)) return 0.0;
    if (largestChange > kMaxLogStep) delta *= kMaxLogStep / largestChange;

    const double rms = current.measure.rms();
    for (std::uint32_t h = 0; h <= kParameterHalvings; ++h) {
      const double fraction = std::ldexp(1.0, -static_cast<int>(h));
      VertexFrameModel candidate = model_;
      for (std::uint32_t k = 0; k < nFrames; ++k) {
        Frame& f = candidate.frames[k];
        const Vec3 amplitude = forceAmplitude(f);
        for (int w = 0; w < 2; ++w) {
          Vec3& a = w == 0 ? f.a1 : f.a2;
          for (int c = 0; c < 3; ++c)
            a[c] = std::clamp(a[c] * std::exp(fraction * delta[6 * k + 3 * w + c]),
                              kMinShapeParameter, kMaxShapeParameter);
        }
        setForceAmplitude(f, amplitude);
      }
      Evaluation next = evaluate(candidate, &current);
      if (!(next.measure.rms() < rms)) continue;
      if (options_.preventFolds && next.measure.foldedSamples > foldLimit(current)) continue;
      model_ = std::move(candidate);
      current = std::move(next);
      rebuildLinear();
      parameterDamping_ = h == 0 ? std::max(kMinParameterDamping, 0.1 * parameterDamping_)
                                 : std::min(kMaxParameterDamping, 10.0 * parameterDamping_);
      return fraction;
    }
    parameterDamping_ = std::min(kMaxParameterDamping, 10.0 * parameterDamping_);
    return 0.0;
  }

  /// The most folded samples a step from `current` may leave (FitOptions::preventFolds).
  static std::uint32_t foldLimit(const Evaluation& current) {
    const auto allowance = static_cast<std::uint32_t>(kFoldAllowance * current.measure.samples);
    return std::max(current.measure.foldedSamples, allowance);
  }

  /// The model at unknowns y (a step from y0) and its evaluation. When the step folds more
  /// samples of some frames over than `current` has there, those frames' vertices stay at
  /// y0 and the rest of the step is tried again (at most kMaxFoldRetries times).
  /// Nothing when every vertex the step moves had to stay.
  std::optional<std::pair<VertexFrameModel, Evaluation>> tryStep(const Eigen::VectorXd& y0,
                                                                 Eigen::VectorXd y,
                                                                 const Evaluation& current) const {
    std::vector<char> kept(model_.vertices.size(), 0);
    for (int retry = 0;; ++retry) {
      VertexFrameModel candidate = modelAt(y);
      Evaluation next = evaluate(candidate, &current);
      if (!options_.preventFolds || retry == kMaxFoldRetries ||
          next.measure.foldedSamples <= foldLimit(current))
        return std::pair{std::move(candidate), std::move(next)};
      bool changed = false;
      for (std::size_t k = 0; k < model_.frames.size(); ++k) {
        if (next.foldsPerFrame[k] <= current.foldsPerFrame[k]) continue;
        for (std::uint32_t v : model_.frames[k].vertices)
          if (!kept[v]) {
            kept[v] = 1;
            y.segment<3>(3 * Eigen::Index{v}) = y0.segment<3>(3 * Eigen::Index{v});
            changed = true;
          }
      }
      if (!changed) return std::pair{std::move(candidate), std::move(next)};
      if (y == y0) return std::nullopt;  // every moving vertex held back: no step left
    }
  }

  /// The umbrella Laplacian over the frame graph: vertex j against the mean of the
  /// vertices next to it along frame sides (P1-P2, P2-P3, ..., P8-P1).
  void buildLaplacian() {
    const std::size_t n = model_.vertices.size();
    std::vector<std::vector<std::uint32_t>> next(n);
    for (const Frame& f : model_.frames)
      for (int i = 0; i < 8; ++i) {
        const std::uint32_t a = f.vertices[i], b = f.vertices[(i + 1) % 8];
        if (a == b) continue;
        next[a].push_back(b);
        next[b].push_back(a);
      }
    std::vector<Eigen::Triplet<double>> triplets;
    for (std::size_t j = 0; j < n; ++j) {
      auto& nj = next[j];
      std::sort(nj.begin(), nj.end());
      nj.erase(std::unique(nj.begin(), nj.end()), nj.end());
      if (nj.empty()) continue;
      triplets.emplace_back(j, j, 1.0);
      for (std::uint32_t k : nj) triplets.emplace_back(j, k, -1.0 / static_cast<double>(nj.size()));
    }
    laplacian_.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
    laplacian_.setFromTriplets(triplets.begin(), triplets.end());
  }

  /// Samples the surface of `model`, pairs the samples with the mesh and the mesh's
  /// vertices with the surface, measures the distances and counts the folded samples.
  /// The closest points are found in parallel, each into its own slot, and summed in order
  /// afterwards: the same result for any number of threads. With `hints` (the evaluation of
  /// a surface near this one, with the same layout) each query starts from the triangle its
  /// closest point was on there: the same closest points, found sooner.
  Evaluation evaluate(const VertexFrameModel& model, const Evaluation* hints = nullptr) const {
    const VertexFrameSurface surface = solve(model, linear_->sharedTopology());
    const std::uint32_t g = samplesPerSide_;
    const auto nFrames = static_cast<std::uint32_t>(surface.patches.size());
    const std::size_t perFrame = grid_.size();
    Evaluation e;
    e.pairs.reserve(std::size_t{nFrames} * perFrame + target_.samples.size());
    const double diag = target_.diagonal > 0.0 ? target_.diagonal : 1.0;

    // Surface samples -> mesh, weighted by the area they stand for.
    const std::size_t count = std::size_t{nFrames} * perFrame;
    std::vector<Vec3> positions(count);
    std::vector<double> cosine(count), distances(count);
    e.pairs.resize(count);
    e.meshTriangle.resize(count);
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, nFrames), [&](const auto& range) {
      for (std::uint32_t k = range.begin(); k != range.end(); ++k) {
        const double flip = surface.topology->flipped[k] ? -1.0 : 1.0;
        for (std::size_t s = 0; s < perFrame; ++s) {
          const std::size_t i = k * perFrame + s;
          const GridPoint& gp = grid_[s];
          const SurfacePoint sp = surface.patches[k].evaluate(gp.u, gp.v);
          positions[i] = sp.p;
          const auto hit =
              hints ? target_.tree.closest_point_and_primitive(
                          toPoint(sp.p), {toPoint(hints->pairs[i].target),
                                          target_.triangles.cbegin() + hints->meshTriangle[i]})
                    : target_.tree.closest_point_and_primitive(toPoint(sp.p));
          const auto t = static_cast<std::size_t>(hit.second - target_.triangles.cbegin());
          e.meshTriangle[i] = static_cast<std::uint32_t>(t);
          const Vec3 foot = toVec(hit.first);
          const Vec3 normal = sp.du.cross(sp.dv);
          const double length = normal.norm();
          cosine[i] = length > 0.0 ? flip * normal.dot(target_.normals[t]) / length : 0.0;
          Pair pair{k,
                    gp.u,
                    gp.v,
                    foot,
                    target_.normals[t],
                    gp.weight * length,
                    static_cast<std::int64_t>(i)};
          const Triangle& tri = target_.triangles[t];
          const Eigen::Vector3d l = barycentric(foot, toVec(tri[0]), toVec(tri[1]), toVec(tri[2]));
          // A foot on an edge or a corner of the triangle is as near to its neighbours: the
          // triangle's own normal is one of several, chosen by how the tree breaks the tie.
          // The direction from the foot to the sample is the distance's gradient there, the
          // same whichever triangle the tree returns.
          const Vec3 away = sp.p - foot;
          if (l.minCoeff() < kOnEdge && away.norm() > kOnEdge * target_.diagonal)
            pair.normal = away.normalized();
          for (int c = 0; c < 3; ++c)
            if ((target_.boundary[t] >> c & 1u) && l[c] < kOnBoundary) pair.normal.setZero();
          distances[i] = (foot - sp.p).norm();
          e.pairs[i] = pair;
        }
      }
    });
    double totalArea = 0.0, agreement = 0.0;
    for (std::size_t i = 0; i < count; ++i) {
      totalArea += e.pairs[i].weight;
      agreement += e.pairs[i].weight * cosine[i];
    }
    if (!(totalArea > 0.0)) throw std::invalid_argument("the model's surface has no area");
    // Folds: samples that disagree with the orientation most of the surface agrees on.
    const double orientation = agreement < 0.0 ? -1.0 : 1.0;
    e.foldsPerFrame.assign(nFrames, 0);
    double sum = 0.0, sumSquares = 0.0, max = 0.0;
    for (std::size_t i = 0; i < count; ++i) {
      e.pairs[i].weight /= totalArea;
      sum += e.pairs[i].weight * distances[i];
      sumSquares += e.pairs[i].weight * distances[i] * distances[i];
      max = std::max(max, distances[i]);
      if (orientation * cosine[i] < 0.0) ++e.foldsPerFrame[e.pairs[i].frame];
    }
    e.measure.samples = static_cast<std::uint32_t>(count);
    for (std::uint32_t f : e.foldsPerFrame) e.measure.foldedSamples += f;
    e.measure.rmsToMesh = std::sqrt(sumSquares) / diag;
    e.measure.meanToMesh = sum / diag;
    e.measure.maxToMesh = max / diag;

    // Mesh vertices -> surface: the closest point on the sample grids' triangles, then
    // Gauss–Newton on that patch from there.
    Triangles cells;
    cells.reserve(std::size_t{nFrames} * 2 * (g - 1) * (g - 1));
    for (std::uint32_t k = 0; k < nFrames; ++k)
      for (std::uint32_t j = 0; j + 1 < g; ++j)
        for (std::uint32_t i = 0; i + 1 < g; ++i) {
          const Vec3* p = &positions[k * perFrame];
          const Point a = toPoint(p[j * g + i]), b = toPoint(p[j * g + i + 1]);
          const Point c = toPoint(p[(j + 1) * g + i + 1]), d = toPoint(p[(j + 1) * g + i]);
          cells.emplace_back(a, b, c);
          cells.emplace_back(a, c, d);
        }
    Tree onSurface(cells.cbegin(), cells.cend());
    onSurface.build();
    // Without hints, a k-d tree of the cells' points starts each query.
    if (!hints) onSurface.accelerate_distance_queries();
    const double cell = 1.0 / (g - 1);
    const FrameTopology& topo = linear_->topology();
    const std::size_t meshCount = target_.samples.size();
    std::vector<double> meshDistances(meshCount);
    e.pairs.resize(count + meshCount);
    e.surfaceCell.resize(meshCount);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, meshCount), [&](const auto& range) {
      for (std::size_t m = range.begin(); m != range.end(); ++m) {
        const Vec3& x = target_.samples[m];
        const std::uint32_t hint = hints ? hints->surfaceCell[m] : 0;
        const auto closest = hints ? onSurface.closest_point_and_primitive(
                                         toPoint(x), {cells[hint].vertex(0), cells.cbegin() + hint})
                                   : onSurface.closest_point_and_primitive(toPoint(x));
        const auto t = static_cast<std::size_t>(closest.second - cells.cbegin());
        e.surfaceCell[m] = static_cast<std::uint32_t>(t);
        const auto k = static_cast<std::uint32_t>(t / (2 * (g - 1) * (g - 1)));
        const std::size_t local = t % (2 * (g - 1) * (g - 1));
        const std::size_t i = (local / 2) % (g - 1), j = (local / 2) / (g - 1);
        // The cell's (u, v) at the closest point, from its barycentric coordinates.
        const Triangle& tri = cells[t];
        const Vec3 a = toVec(tri[0]), b = toVec(tri[1]), c = toVec(tri[2]);
        const Vec3 pc = toVec(closest.first);
        const double total = (b - a).cross(c - a).norm();
        double lb = 0.0, lc = 0.0;
        if (total > 0.0) {
          lb = (pc - a).cross(c - a).norm() / total;
          lc = (b - a).cross(pc - a).norm() / total;
        }
        // Corners in (u, v): a = (i, j); first triangle b = (i+1, j), c = (i+1, j+1);
        // second triangle b = (i+1, j+1), c = (i, j+1).
        double du, dv;
        if (local % 2 == 0)
          du = lb + lc, dv = lc;
        else
          du = lb, dv = lb + lc;
        double u = (static_cast<double>(i) + du) * cell, v = (static_cast<double>(j) + dv) * cell;
        const VertexFramePatch& patch = surface.patches[k];
        double best = (patch.position(u, v) - x).squaredNorm();
        double bu = u, bv = v;
        for (int step = 0; step < kProjectionSteps; ++step) {
          const SurfacePoint sp = patch.evaluate(u, v);
          const Vec3 r = sp.p - x;
          Eigen::Matrix2d jtj;
          jtj << sp.du.dot(sp.du), sp.du.dot(sp.dv), sp.du.dot(sp.dv), sp.dv.dot(sp.dv);
          const Eigen::Vector2d jtr(sp.du.dot(r), sp.dv.dot(r));
          if (!(jtj.determinant() > 0.0)) break;
          const Eigen::Vector2d delta = jtj.ldlt().solve(-jtr);
          u = std::clamp(u + delta.x(), 0.0, 1.0);
          v = std::clamp(v + delta.y(), 0.0, 1.0);
          const double d2 = (patch.position(u, v) - x).squaredNorm();
          if (d2 < best) best = d2, bu = u, bv = v;
        }
        meshDistances[m] = std::sqrt(best);
        const SurfacePoint foot = patch.evaluate(bu, bv);
        const Vec3 normal = foot.du.cross(foot.dv);
        const double length = normal.norm();
        // A foot on a side no other frame shares is on the surface's boundary.
        bool onBoundary = false;
        const std::array<bool, 4> atSide = {bv == 0.0, bu == 1.0, bv == 1.0, bu == 0.0};
        for (int side = 0; side < 4; ++side)
          if (atSide[side] && topo.edges[topo.edgeOf[k][side]].sideCount == 1) onBoundary = true;
        e.pairs[count + m] = {k,
                              bu,
                              bv,
                              x,
                              length > 0.0 && !onBoundary ? Vec3(normal / length) : Vec3::Zero(),
                              target_.weights[m],
                              -1};
      }
    });
    sum = sumSquares = max = 0.0;
    for (std::size_t m = 0; m < meshCount; ++m) {
      const double w = target_.weights[m], dist = meshDistances[m];
      sum += w * dist;
      sumSquares += w * dist * dist;
      max = std::max(max, dist);
    }
    e.measure.rmsToModel = std::sqrt(sumSquares) / diag;
    e.measure.meanToModel = sum / diag;
    e.measure.maxToModel = max / diag;
    return e;
  }

  /// The unknowns y that minimise the paired squared distances plus the smoothness term,
  /// with each strip's cubic coefficient tied to the vertices as the global solver ties it.
  /// Written with the strip values X as unknowns too, z = (y, X), the objective is a sparse
  /// quadratic ½ zᵀKz - bᵀz (local couplings only), and X = L y, so y minimises
  /// ½ yᵀ(PᵀKP)y - (Pᵀb)ᵀy with P = [I; L]. PᵀKP couples whole strips (dense), so it is
  /// never formed: conjugate gradients apply it as products with K and L, preconditioned by
  /// the sparse Cholesky factor of K's local block K_yy (its pattern analysed once), and
  /// start from the current unknowns y0.
  Eigen::VectorXd leastSquares(const std::vector<Pair>& pairs, const Eigen::VectorXd& y0) {
    return shape_ ? leastSquares<11>(pairs, y0) : leastSquares<10>(pairs, y0);
  }

  /// Slots: a frame's unknowns, 8 vertices and 2 strips, and in the shape phase (11) its
  /// force's amplitude, whose weight at (u, v) is sin(πu) sin(πv).
  template <int Slots>
  Eigen::VectorXd leastSquares(const std::vector<Pair>& pairs, const Eigen::VectorXd& y0) {
    const auto n = static_cast<Eigen::Index>(model_.vertices.size());
    const auto strips = static_cast<Eigen::Index>(linear_->stripCount());
    const Eigen::Index free = y0.size(), size = free + 3 * strips;
    const auto nFrames = model_.frames.size();
    const auto& topo = linear_->topology();
    // Unknown (slot i of frame k, component c) at 3 × (vertex, n + frame for the force, or
    // free / 3 + strip) + c.
    auto unknown = [&](std::size_t k, int i) {
      return i < 8    ? Eigen::Index{model_.frames[k].vertices[i]}
             : i < 10 ? free / 3 + Eigen::Index{topo.strip[k][i - 8]}
                      : n + static_cast<Eigen::Index>(k);
    };
    // Per frame, the 3 Slots × 3 Slots normal block of its unknowns: Σ w (a aᵀ) ⊗ M.
    using Block = Eigen::Matrix<double, 3 * Slots, 3 * Slots>;
    std::vector<Block> blocks(nFrames, Block::Zero());
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(size);
    const double mu = tangentialWeight_;
    for (const Pair& p : pairs) {
      const PointWeights w = p.sample >= 0 ? gridWeights_[static_cast<std::size_t>(p.sample)]
                                           : linear_->weights(p.frame, p.u, p.v);
      Eigen::Matrix<double, Slots, 1> a;
      for (int i = 0; i < 8; ++i) a[i] = w.vertex[i];
      a[8] = w.strip[0];
      a[9] = w.strip[1];
      if constexpr (Slots == 11)
        a[10] = detail::forceShape(p.u, 0.0, 1.0).s * detail::forceShape(p.v, 0.0, 1.0).s;
      const Eigen::Matrix3d m =
          mu * Eigen::Matrix3d::Identity() + (1.0 - mu) * p.normal * p.normal.transpose();
      const Eigen::Matrix<double, Slots, Slots> aa = p.weight * a * a.transpose();
      Block& block = blocks[p.frame];
      for (int i = 0; i < Slots; ++i)
        for (int j = 0; j < Slots; ++j) block.template block<3, 3>(3 * i, 3 * j) += aa(i, j) * m;
      const Vec3 mt = m * (p.target - w.offset);
      for (int i = 0; i < Slots; ++i)
        rhs.segment<3>(3 * unknown(p.frame, i)) += p.weight * a[i] * mt;
    }
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(nFrames * 9 * Slots * Slots);
    std::vector<char> used(static_cast<std::size_t>(n), 0);
    for (std::size_t k = 0; k < nFrames; ++k) {
      for (std::uint32_t v : model_.frames[k].vertices) used[v] = 1;
      for (int i = 0; i < Slots; ++i)
        for (int j = 0; j < Slots; ++j)
          for (int c = 0; c < 3; ++c)
            for (int d = 0; d < 3; ++d)
              triplets.emplace_back(3 * unknown(k, i) + c, 3 * unknown(k, j) + d,
                                    blocks[k](3 * i + c, 3 * j + d));
    }
    // Vertices no frame uses stay where they are.
    for (Eigen::Index j = 0; j < n; ++j)
      if (!used[j])
        for (int c = 0; c < 3; ++c) {
          triplets.emplace_back(3 * j + c, 3 * j + c, 1.0);
          rhs[3 * j + c] = y0[3 * j + c];
        }
    // Smoothness: (λ / n) Σ_j |Lap x|², the Laplacian acting on each component alike.
    if (options_.smoothness > 0.0) {
      const Eigen::SparseMatrix<double> lap2 = laplacian_.transpose() * laplacian_;
      const double scale = options_.smoothness / static_cast<double>(n);
      for (Eigen::Index col = 0; col < lap2.outerSize(); ++col)
        for (Eigen::SparseMatrix<double>::InnerIterator it(lap2, col); it; ++it)
          for (int c = 0; c < 3; ++c)
            triplets.emplace_back(3 * it.row() + c, 3 * it.col() + c, scale * it.value());
    }
    Eigen::SparseMatrix<double> k(size, size);
    k.setFromTriplets(triplets.begin(), triplets.end());
    const Eigen::SparseMatrix<double> local = k.topLeftCorner(free, free);
    if (local.nonZeros() != analysedNonZeros_) {
      factor_.analyzePattern(local);
      analysedNonZeros_ = local.nonZeros();
    }
    factor_.factorize(local);
    if (factor_.info() != Eigen::Success)
      throw std::runtime_error(
          "the fit's least-squares system is singular (a vertex no sample depends on)");
    const auto& factor = factor_;

    // Preconditioned conjugate gradients on (PᵀKP) y = Pᵀb from y0.
    auto apply = [&](const Eigen::VectorXd& y) {
      Eigen::VectorXd z(size);
      z.head(free) = y;
      z.tail(3 * strips) = strips_ * y;
      const Eigen::VectorXd kz = k * z;
      return Eigen::VectorXd(kz.head(free) + strips_.transpose() * kz.tail(3 * strips));
    };
    const Eigen::VectorXd b = rhs.head(free) + strips_.transpose() * rhs.tail(3 * strips);
    // Solved to kCgTolerance of the right-hand side, or kCgReduction of the residual at y0.
    return conjugateGradients(
        apply, [&](const Eigen::VectorXd& r) { return Eigen::VectorXd(factor.solve(r)); }, b, y0,
        kCgTolerance, kCgReduction);
  }

  VertexFrameModel model_;
  Target target_;
  FitOptions options_;
  std::uint32_t samplesPerSide_ = 9;
  std::vector<GridPoint> grid_;
  std::unique_ptr<LinearSurface> linear_;
  std::vector<PointWeights> gridWeights_;  ///< per frame, per grid point
  /// The strip values as rows on the unknowns, 3 × strips by 3 × vertices (component c of
  /// strip s in row 3s + c).
  Eigen::SparseMatrix<double, Eigen::RowMajor> strips_;
  double tangentialWeight_ = 1.0;
  bool shape_ = false;  ///< the shape phase: forces among the unknowns, a1 and a2 stepped
  double parameterDamping_ = kStartParameterDamping;  ///< λ of parameterStep
  Eigen::SparseMatrix<double> laplacian_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor_;
  Eigen::Index analysedNonZeros_ = -1;  ///< of the pattern factor_ analysed (-1: none yet)
};

}  // namespace

FitResult fitVertexFrames(const VertexFrameModel& start, const Mesh& target,
                          const FitOptions& options) {
  if (options.samplesPerSide != 0 && options.samplesPerSide < 3)
    throw std::invalid_argument("fit: samplesPerSide must be 0 (automatic) or at least 3");
  if (options.fitShape) {
    if (!start.forces.empty())
      throw std::invalid_argument(
          fmt::format("fit: the shape fit sets a force on every frame, but the start model has "
                      "{} shared force(s) already",
                      start.forces.size()));
    for (std::size_t k = 0; k < start.frames.size(); ++k) {
      const Frame& f = start.frames[k];
      if (!f.forces.empty())
        throw std::invalid_argument(
            fmt::format("fit: the shape fit sets a force on every frame, but frame {} of the "
                        "start model has {} force(s) already",
                        k, f.forces.size()));
      for (int w = 0; w < 2; ++w)
        for (int c = 0; c < 3; ++c) {
          const double a = (w == 0 ? f.a1 : f.a2)[c];
          if (!(a >= kMinShapeParameter && a <= kMaxShapeParameter))
            throw std::invalid_argument(fmt::format(
                "fit: frame {} has a{}.{} = {}, outside the range the shape fit keeps a1 and a2 "
                "in, [{}, {}]",
                k, w + 1, "xyz"[c], a, kMinShapeParameter, kMaxShapeParameter));
        }
    }
  }
  Fitter fitter(start, target, options);
  return fitter.run();
}

}  // namespace pdesurf
