// Fitting a vertex-frame model to a mesh: closest points both ways (closest_pairs.cpp), a
// sparse linear least-squares step in the vertex positions with the strips' cubic
// coefficients tied to them exactly, and a line search on the measured RMS; with the shape fit
// also each frame's force and a1, a2 (shape_step.cpp; docs/rebuild.md).
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "fit/closest_pairs.hpp"
#include "fit/conjugate_gradients.hpp"
#include "fit/linear_surface.hpp"
#include "fit/shape_step.hpp"
#include "numerics/force_shape.hpp"
#include "pdesurf/error.hpp"
#include "pdesurf/rebuild.hpp"

namespace pdesurf {

double FitMeasure::rms() const {
  return std::sqrt(0.5 * (rmsToMesh * rmsToMesh + rmsToModel * rmsToModel));
}

namespace {

using fit::Evaluation;
using fit::LinearSurface;
using fit::Pair;
using fit::PointWeights;
using fit::SampleGrid;
using fit::Target;

/// Below this RMS relative to the diagonal the fit is exact to rounding (float meshes
/// carry 6e-8 relative): nothing is left to lower.
constexpr double kExactRms = 1e-14;

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
/// A step may fold over up to this share of the samples even where the surface had fewer
/// folded ones: at a cliff or near the mesh's boundary a sample's closest point can lie on
/// a triangle that faces away, which is no fold of the surface, and holding every such
/// sample would stall the fit (three_peaks.off: RMS 1.3 % instead of 0.16 %).
constexpr double kFoldAllowance = 0.005;
/// A frame whose samples weigh less than this share of the mean frame's is taken as weighing
/// nothing (a frame shrunk to a point): its vertices that no other frame weighs are anchored
/// where they are (the least squares, below).
constexpr double kUnweightedFrame = 1e-9;

/// The Jacobian barrier (addTangentTerms): a sample's determinant (S_u × S_v)·m is held above
/// this share of its frame's mean |S_u × S_v| ...
constexpr double kBarrierFloor = 0.1;
/// ... with this many times the fold-free term's weight λ (the folded area at 100 frames on
/// three_peaks, lion-head, pig and bear: ratios 30 and 100 leave the bear 0.73–0.75 %
/// folded, 1000 folds the lion 0.11 %, 300 folds under 0.06 % on all four; docs/rebuild.md).
constexpr double kBarrierRatio = 300.0;

/// Where a step would fold more samples of some frames over, those frames' vertices stay
/// and the rest of the step is tried again, at most this many times a step.
constexpr int kMaxFoldRetries = 4;

/// The a1, a2 step of the shape fit (parameterStep): Levenberg–Marquardt damping λ, relative
/// to the diagonal of the Gauss–Newton matrix, starting here, divided by 10 after a whole
/// step and multiplied by 10 after a halved or failed one, within these bounds ...
constexpr double kStartParameterDamping = 1e-2;
constexpr double kMinParameterDamping = 1e-6;
constexpr double kMaxParameterDamping = 1e6;
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
      : model_(start),
        target_(target),
        options_(options),
        grid_(options.samplesPerSide != 0
                  ? options.samplesPerSide
                  : automaticSamples(target_.samples.size(), start.frames.size())) {
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
        const Eigen::VectorXd solution = leastSquares(current, y0);
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
    const std::vector<SampleGrid::Point>& grid = grid_.points;
    gridWeights_.resize(nFrames * grid.size());
    for (std::uint32_t k = 0; k < nFrames; ++k)
      for (std::size_t s = 0; s < grid.size(); ++s)
        gridWeights_[k * grid.size() + s] = linear_->weights(k, grid[s].u, grid[s].v);
    gridDerivatives_.resize(2 * nFrames * grid.size());
    for (std::uint32_t k = 0; k < nFrames; ++k)
      for (std::size_t s = 0; s < grid.size(); ++s)
        for (int d = 0; d < 2; ++d)
          gridDerivatives_[(k * grid.size() + s) * 2 + d] =
              linear_->derivativeWeights(k, grid[s].u, grid[s].v, d);
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
        y.segment<3>(3 * static_cast<Eigen::Index>(n + k)) =
            fit::wholeFrameForceAmplitude(model_.frames[k]);
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
        fit::setWholeFrameForceAmplitude(m.frames[k],
                                         y.segment<3>(3 * static_cast<Eigen::Index>(n + k)));
    return m;
  }

  /// The shape phase: the forces join the unknowns (their f0 from now on follows a1 and
  /// a2 so that the amplitude stays when those change).
  void enableShape() {
    shape_ = true;
    rebuildLinear();
  }

  /// One damped Gauss–Newton step in ln a1 and ln a2 (fit::parameterDirection) from
  /// `current`, taken whole, else halved, only where the measured RMS falls. Returns the
  /// fraction taken (0: none). Its Levenberg–Marquardt damping adapts as the tangential
  /// weight does.
  double parameterStep(Evaluation& current) {
    const std::optional<Eigen::VectorXd> direction =
        fit::parameterDirection(*linear_, model_, current, tangentialWeight_, parameterDamping_);
    if (!direction) return 0.0;
    const double rms = current.measure.rms();
    for (std::uint32_t h = 0; h <= kParameterHalvings; ++h) {
      const double fraction = std::ldexp(1.0, -static_cast<int>(h));
      VertexFrameModel candidate = fit::withParameterStep(model_, *direction, fraction);
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

  /// The closest-point pairs of `model`'s surface and the mesh (fit::closestPairs), from the
  /// closest points of `hints` (an evaluation of a near surface) when given.
  Evaluation evaluate(const VertexFrameModel& model, const Evaluation* hints = nullptr) const {
    return fit::closestPairs(solve(model, linear_->sharedTopology()), grid_, target_, hints);
  }

  /// Per frame, the aspect ρ_k = sqrt(∫∫|S_v|² / ∫∫|S_u|²) of the surface `e` measured (0
  /// for a frame with no extent), and the surface's area A = Σ_k ∫∫ |S_u × S_v| du dv.
  struct Aspects {
    std::vector<double> rho;
    std::vector<double> jacobian;  ///< per frame, the mean |S_u × S_v| over (u, v)
    double area = 0.0;
  };
  Aspects aspects(const Evaluation& e) const {
    const std::vector<SampleGrid::Point>& grid = grid_.points;
    const std::size_t nFrames = model_.frames.size(), perFrame = grid.size();
    Aspects out{std::vector<double>(nFrames, 0.0), std::vector<double>(nFrames, 0.0)};
    for (std::size_t k = 0; k < nFrames; ++k) {
      double uu = 0.0, vv = 0.0, area = 0.0;
      for (std::size_t s = 0; s < perFrame; ++s) {
        const std::size_t i = k * perFrame + s;
        uu += grid[s].weight * e.du[i].squaredNorm();
        vv += grid[s].weight * e.dv[i].squaredNorm();
        area += grid[s].weight * cellArea() * e.du[i].cross(e.dv[i]).norm();
      }
      out.area += area;
      out.jacobian[k] = area;  // the unit square's area is 1
      if (uu > 0.0 && vv > 0.0) out.rho[k] = std::sqrt(vv / uu);
    }
    return out;
  }

  /// The area in (u, v) a sample's unit weight stands for: the grid's weights sum to
  /// (g - 1)², the unit square's area to 1.
  double cellArea() const { return 1.0 / ((grid_.perSide - 1.0) * (grid_.perSide - 1.0)); }

  /// The unit normal that sample i of frame k should turn to: the mesh's at its closest point,
  /// turned as the surface mostly faces and as the frame is flipped (so that S_u × S_v · m > 0
  /// where the frame faces as the rest does).
  Vec3 facing(const Evaluation& e, std::size_t k, std::size_t i) const {
    const double flip = linear_->topology().flipped[k] ? -1.0 : 1.0;
    return flip * e.orientation * target_.normals[e.meshTriangle[i]];
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

  /// The terms on the patches' tangents S_u, S_v at the surface samples: the fold-free term,
  /// the Jacobian barrier that comes with it, and the normal-alignment term, each added where
  /// its weight is above 0.
  ///
  /// The fold-free term (FitOptions::conformalWeight; docs/rebuild.md, "Folds"): per surface
  /// sample (frame k, u, v), with m the mesh's normal at its closest point turned to the way
  /// the frame must face (the surface's majority orientation, the frame's flip), the residual
  /// r = S_v - ρ_k m × S_u, zero where the patch maps a square of (u, v) to a rectangle of
  /// aspect ρ_k in the tangent plane, turning as the mesh does. |r|² = |S_v|² + ρ²|S_u⊥|²
  /// - 2ρ (S_u × S_v)·m + ρ²(S_u·m)²: it penalises a tangent leaving the tangent plane, a
  /// Jacobian that shears, and above all one whose determinant turns negative (a fold).
  /// S_u, S_v are affine in the unknowns and m, ρ_k are frozen at the current iterate, so
  /// the term is quadratic: weight λ diag² / A · Σ_k ∫∫ |r|² du dv, A the surface's area and
  /// ρ_k² = ∫∫|S_v|² / ∫∫|S_u|² over frame k. Added into the frames' normal blocks.
  ///
  /// The Jacobian barrier (kBarrierRatio λ; docs/rebuild.md, "The Jacobian barrier"): at the
  /// samples where the determinant d = (S_u × S_v)·m is below τ J_k (J_k the frame's mean
  /// |S_u × S_v|), the residual (τ J_k - d) / sqrt(J_k), d linearised at the current iterate
  /// (δd = δS_u·(S_v × m) + δS_v·(m × S_u)), weighted β diag² / A as above: it pushes the
  /// determinant of the samples about to fold, or folded, back up, and nothing else. Both
  /// terms are off where λ = 0 (the distances alone).
  ///
  /// The normal-alignment term (FitOptions::normalWeight ν; docs/rebuild.md, "Normals"): per
  /// sample and tangent T = S_u, S_v, the residual T·m / |T| (the sine of T's tilt out of the
  /// mesh's tangent plane, |T| frozen at the current iterate, so linear in the unknowns),
  /// weighted ν diag² w_i, w_i the sample's share of the surface's area: the rank-one
  /// (a ⊗ m)(a ⊗ m)ᵀ per tangent in the frame's normal block.
  template <int Slots, class Blocks, class Unknown>
  void addTangentTerms(const Evaluation& current, Blocks& blocks, Eigen::VectorXd& rhs,
                       const Unknown& unknown) const {
    using Weights = Eigen::Matrix<double, Slots, 1>;
    const std::vector<SampleGrid::Point>& grid = grid_.points;
    const std::size_t nFrames = model_.frames.size(), perFrame = grid.size();
    const Aspects aspect = aspects(current);
    if (!(aspect.area > 0.0)) return;
    const double unit = target_.diagonal * target_.diagonal * cellArea() / aspect.area;
    const double conformal = options_.conformalWeight * unit;
    const double barrier = kBarrierRatio * conformal;
    const double alignment = options_.normalWeight * target_.diagonal * target_.diagonal;
    for (std::size_t k = 0; k < nFrames; ++k) {
      const double rho = aspect.rho[k], jacobian = aspect.jacobian[k];
      auto& block = blocks[k];
      for (std::size_t s = 0; s < perFrame; ++s) {
        const std::size_t i = k * perFrame + s;
        // S_u = Σ aᵢ xᵢ + offU and S_v = Σ bᵢ xᵢ + offV over the frame's unknowns.
        const PointWeights& wu = gridDerivatives_[2 * i];
        const PointWeights& wv = gridDerivatives_[2 * i + 1];
        Weights a, b;
        for (int p = 0; p < 8; ++p) a[p] = wu.vertex[p], b[p] = wv.vertex[p];
        for (int d = 0; d < 2; ++d) a[8 + d] = wu.strip[d], b[8 + d] = wv.strip[d];
        if constexpr (Slots == 11) {
          const detail::ForceShape fu = detail::forceShape(grid[s].u, 0.0, 1.0);
          const detail::ForceShape fv = detail::forceShape(grid[s].v, 0.0, 1.0);
          a[10] = fu.ds * fv.s;
          b[10] = fu.s * fv.ds;
        }
        const Vec3 m = facing(current, k, i);
        if (conformal > 0.0 && rho > 0.0) {
          Eigen::Matrix3d n;  // n x = m × x
          n << 0.0, -m.z(), m.y(), m.z(), 0.0, -m.x(), -m.y(), m.x(), 0.0;
          const Eigen::Matrix3d tangential = Eigen::Matrix3d::Identity() - m * m.transpose();
          const double c = conformal * grid[s].weight;
          // r = Σ_p G_p x_p + r0, G_p = b_p I - ρ a_p N: G_pᵀG_q = b_p b_q I + ρ(a_p b_q -
          // b_p a_q) N + ρ² a_p a_q (I - m mᵀ), as Nᵀ = -N and NᵀN = I - m mᵀ.
          for (int p = 0; p < Slots; ++p)
            for (int q = 0; q < Slots; ++q)
              block.template block<3, 3>(3 * p, 3 * q) +=
                  c *
                  (b[p] * b[q] * Eigen::Matrix3d::Identity() +
                   rho * (a[p] * b[q] - b[p] * a[q]) * n + rho * rho * a[p] * a[q] * tangential);
          const Vec3 r0 = wv.offset - rho * m.cross(wu.offset);
          for (int p = 0; p < Slots; ++p)
            rhs.segment<3>(3 * unknown(k, p)) -= c * (b[p] * r0 + rho * a[p] * m.cross(r0));
        }
        const Vec3 su = current.du[i], sv = current.dv[i];
        if (alignment > 0.0) {
          // The normal-alignment term: each tangent T = Σ w_p x_p + offset (S_u, S_v: affine
          // in the unknowns) tilted out of the mesh's tangent plane, the residual T·m / |T|
          // (|T| frozen), weighted by the sample's share of the surface's area.
          auto addTilt = [&](const Weights& w, const Vec3& offset, double length2) {
            if (!(length2 > 0.0)) return;
            const double c = alignment * current.pairs[i].weight / length2;
            Eigen::Matrix<double, 3 * Slots, 1> g;
            for (int p = 0; p < Slots; ++p) g.template segment<3>(3 * p) = w[p] * m;
            block.noalias() += c * g * g.transpose();
            const double t = m.dot(offset);
            for (int p = 0; p < Slots; ++p)
              rhs.segment<3>(3 * unknown(k, p)) -= c * t * g.template segment<3>(3 * p);
          };
          addTilt(a, wu.offset, su.squaredNorm());
          addTilt(b, wv.offset, sv.squaredNorm());
        }
        const double det = su.cross(sv).dot(m), floor = kBarrierFloor * jacobian;
        if (barrier > 0.0 && jacobian > 0.0 && det < floor) {
          // d(x) ≈ Σ_p g_pᵀ x_p - d0 + offU·(S_v × m) + offV·(m × S_u), g_p = a_p (S_v × m)
          // + b_p (m × S_u) (Σ_p g_pᵀ x0_p = 2 d0 - the offsets' part); the residual
          // floor - d(x) = t - Σ_p g_pᵀ x_p.
          const Vec3 gu = sv.cross(m), gv = m.cross(su);
          const double t = floor + det - wu.offset.dot(gu) - wv.offset.dot(gv);
          const double c = barrier * grid[s].weight / jacobian;
          Eigen::Matrix<double, 3 * Slots, 1> g;
          for (int p = 0; p < Slots; ++p) g.template segment<3>(3 * p) = a[p] * gu + b[p] * gv;
          block.noalias() += c * g * g.transpose();
          for (int p = 0; p < Slots; ++p)
            rhs.segment<3>(3 * unknown(k, p)) += c * t * g.template segment<3>(3 * p);
        }
      }
    }
  }

  /// The unknowns y that minimise the paired squared distances plus the smoothness term,
  /// with each strip's cubic coefficient tied to the vertices as the global solver ties it.
  /// Written with the strip values X as unknowns too, z = (y, X), the objective is a sparse
  /// quadratic ½ zᵀKz - bᵀz (local couplings only), and X = L y, so y minimises
  /// ½ yᵀ(PᵀKP)y - (Pᵀb)ᵀy with P = [I; L]. PᵀKP couples whole strips (dense), so it is
  /// never formed: conjugate gradients apply it as products with K and L, preconditioned by
  /// the sparse Cholesky factor of K's local block K_yy (its pattern analysed once), and
  /// start from the current unknowns y0.
  Eigen::VectorXd leastSquares(const Evaluation& current, const Eigen::VectorXd& y0) {
    return shape_ ? leastSquares<11>(current, y0) : leastSquares<10>(current, y0);
  }

  /// Slots: a frame's unknowns, 8 vertices and 2 strips, and in the shape phase (11) its
  /// force's amplitude, whose weight at (u, v) is sin(πu) sin(πv).
  template <int Slots>
  Eigen::VectorXd leastSquares(const Evaluation& current, const Eigen::VectorXd& y0) {
    const std::vector<Pair>& pairs = current.pairs;
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
    if (options_.conformalWeight > 0.0 || options_.normalWeight > 0.0)
      addTangentTerms<Slots>(current, blocks, rhs, unknown);
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
    // Vertices that no sample weighs stay where they are: a frame the fit shrank to a point
    // has no area, so its samples weigh nothing, and the smoothness term does not see it move
    // whole, so the system is singular in its vertices (CGAL's boeing.off at 60 frames: one
    // such frame flew 2,000 units off, 74 diagonals). Each vertex used only by frames whose
    // samples weigh less than kUnweightedFrame of the mean frame's gets an anchor μ |y - y0|²
    // with μ the mean diagonal of the vertices' equations; the others are not touched.
    {
      std::vector<double> frameWeight(nFrames, 0.0);
      for (const Pair& p : pairs) frameWeight[p.frame] += p.weight;
      double meanWeight = 0.0;
      for (double w : frameWeight) meanWeight += w / static_cast<double>(nFrames);
      std::vector<char> weighed(static_cast<std::size_t>(n), 0);
      for (std::size_t f = 0; f < nFrames; ++f)
        if (frameWeight[f] > kUnweightedFrame * meanWeight)
          for (std::uint32_t v : model_.frames[f].vertices) weighed[v] = 1;
      double trace = 0.0;
      for (Eigen::Index j = 0; j < 3 * n; ++j) trace += k.coeff(j, j);
      const double anchor = trace / static_cast<double>(3 * n);
      for (Eigen::Index v = 0; v < n; ++v)
        if (used[v] && !weighed[v])
          for (Eigen::Index c = 3 * v; c < 3 * v + 3; ++c) {
            k.coeffRef(c, c) += anchor;
            rhs[c] += anchor * y0[c];
          }
    }
    const Eigen::SparseMatrix<double> local = k.topLeftCorner(free, free);
    if (local.nonZeros() != analysedNonZeros_) {
      factor_.analyzePattern(local);
      analysedNonZeros_ = local.nonZeros();
    }
    factor_.factorize(local);
    if (factor_.info() != Eigen::Success)
      throw Error("the fit's least-squares system is singular (a vertex no sample depends on)");
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
    return fit::conjugateGradients(
        apply, [&](const Eigen::VectorXd& r) { return Eigen::VectorXd(factor.solve(r)); }, b, y0,
        kCgTolerance, kCgReduction);
  }

  VertexFrameModel model_;
  Target target_;
  FitOptions options_;
  SampleGrid grid_;  ///< the surface samples on every patch
  std::unique_ptr<LinearSurface> linear_;
  std::vector<PointWeights> gridWeights_;      ///< per frame, per grid point
  std::vector<PointWeights> gridDerivatives_;  ///< per frame, per grid point: S_u's, S_v's
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
    throw InvalidArgument("fit: samplesPerSide must be 0 (automatic) or at least 3");
  if (!(options.normalWeight >= 0.0 && std::isfinite(options.normalWeight)))
    throw InvalidArgument(fmt::format("fit: normalWeight must be finite and at least 0, got {}",
                                      options.normalWeight));
  if (options.fitShape) {
    if (!start.forces.empty())
      throw InvalidArgument(
          fmt::format("fit: the shape fit sets a force on every frame, but the start model has "
                      "{} shared force(s) already",
                      start.forces.size()));
    for (std::size_t k = 0; k < start.frames.size(); ++k) {
      const Frame& f = start.frames[k];
      if (!f.forces.empty())
        throw InvalidArgument(
            fmt::format("fit: the shape fit sets a force on every frame, but frame {} of the "
                        "start model has {} force(s) already",
                        k, f.forces.size()));
      for (int w = 0; w < 2; ++w)
        for (int c = 0; c < 3; ++c) {
          const double a = (w == 0 ? f.a1 : f.a2)[c];
          if (!(a >= kMinShapeParameter && a <= kMaxShapeParameter))
            throw InvalidArgument(fmt::format(
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
