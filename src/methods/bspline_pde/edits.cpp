// The shape edits of B-spline PDE models (bspline_pde/edits.hpp).
#include "methods/bspline_pde/edits.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>

#include "pdesurf/bspline_pde_io.hpp"

namespace pdesurf::detail {

namespace {

using Form = BSplinePdeModel::Form;

/// The B-spline PDE curves by their file names, per form.
constexpr const char* kSideNames[] = {"uMin", "uMax", "vMin", "vMax"};
constexpr const char* kClosedNames[] = {"start", "end"};
constexpr const char* kSecondNames[] = {"uMinSecond", "vMinSecond"};

std::vector<Vec3>& pointsOf(BoundaryCurve& c) {
  return std::visit([](auto& x) -> std::vector<Vec3>& { return x.points; }, c);
}
const std::vector<Vec3>& pointsOf(const BoundaryCurve& c) {
  return std::visit([](const auto& x) -> const std::vector<Vec3>& { return x.points; }, c);
}

/// The curves of a B-spline PDE model whose ends may be shared corners (the boundary form's
/// four sides, a blend's four curves, a closed blend's two closed curves), as point lists.
std::vector<std::vector<Vec3>*> cornerCurves(BSplinePdeModel& m) {
  std::vector<std::vector<Vec3>*> out;
  if (m.form == Form::Boundary)
    for (BoundaryCurve* c :
         {&m.boundary.uMin, &m.boundary.uMax, &m.boundary.vMin, &m.boundary.vMax})
      out.push_back(&pointsOf(*c));
  if (m.form == Form::Blend || m.form == Form::ClosedBlend)
    for (BSplineCurve& c : m.curves) out.push_back(&c.points);
  return out;
}

/// Cumulative chord length of `points`, from 0 to 1 (uniform when they all coincide).
std::vector<double> chordParameters(const std::vector<Vec3>& points) {
  std::vector<double> t = {0.0};
  for (std::size_t k = 1; k < points.size(); ++k) {
    const Vec3 d = points[k] - points[k - 1];
    t.push_back(t[k - 1] + std::hypot(d.x(), d.y(), d.z()));
  }
  const double total = t.back();
  for (std::size_t k = 0; k < t.size(); ++k)
    t[k] = total > 0.0 ? t[k] / total
                       : static_cast<double>(k) /
                             static_cast<double>(std::max<std::size_t>(points.size() - 1, 1));
  return t;
}

/// The polyline through `points` at parameters `t` (increasing, 0 to 1), at `s`.
Vec3 alongPolyline(const std::vector<Vec3>& points, const std::vector<double>& t, double s) {
  std::size_t k = 1;
  while (k < points.size() - 1 && t[k] < s) ++k;
  const double span = t[k] - t[k - 1];
  const double w = span > 0.0 ? std::clamp((s - t[k - 1]) / span, 0.0, 1.0) : 0.0;
  return points[k - 1] + w * (points[k] - points[k - 1]);
}

/// A tangent row's vectors and the points on `side` they are drawn from: at their parameters
/// (given, else uniform) on the side (at its samples' parameters, else chord length).
void addTangentRow(ModelHandles& out, const char* name, const TangentCurve& tangent,
                   const BoundaryCurve& side) {
  const std::vector<Vec3>& at = pointsOf(tangent.vectors);
  const std::vector<Vec3>& sidePoints = pointsOf(side);
  const auto* samples = std::get_if<CurveSamples>(&tangent.vectors);
  std::vector<double> t;
  if (samples && !samples->t.empty()) {
    t = samples->t;
  } else {
    for (std::size_t k = 0; k < at.size(); ++k)
      t.push_back(static_cast<double>(k) /
                  static_cast<double>(std::max<std::size_t>(at.size() - 1, 1)));
  }
  const auto* sideSamples = std::get_if<CurveSamples>(&side);
  const std::vector<double> sideT =
      sideSamples && !sideSamples->t.empty() ? sideSamples->t : chordParameters(sidePoints);
  std::vector<Vec3> base;
  for (const double x : t) base.push_back(alongPolyline(sidePoints, sideT, x));
  const CurveRef ref{0, name};
  addCurve(out, ref, fmt::format("{} (tangent)", name), nullptr, Vec3::Zero(), true);
  addTangents(out, ref, at, base, false);
}

CurveTarget bsplineCurve(BSplinePdeModel& m, const CurveRef& ref, const std::string& path) {
  const ModelReader rd("edit");
  if (m.form == Form::Boundary) {
    BoundaryInput& b = m.boundary;
    BoundaryCurve* sides[] = {&b.uMin, &b.uMax, &b.vMin, &b.vMax};
    for (int s = 0; s < 4; ++s)
      if (ref.name == kSideNames[s])
        return {nullptr, &pointsOf(*sides[s]), false, "$.boundary." + ref.name};
    for (auto [name, row] : {std::pair{"uMinSecond", &b.uMinSecond}, {"vMinSecond", &b.vMinSecond}})
      if (ref.name == name) {
        if (auto* points = std::get_if<std::vector<Vec3>>(row))
          return {nullptr, points, false, fmt::format("$.boundary.{}.points", name)};
        return {nullptr, &pointsOf(std::get<TangentCurve>(*row).vectors), true,
                fmt::format("$.boundary.{}.tangent", name)};
      }
    rd.fail(path, fmt::format("the boundary form has no curve \"{}\" (its curves: uMin, uMax, "
                              "vMin, vMax, uMinSecond, vMinSecond)",
                              ref.name));
  }
  if (m.form == Form::Blend || m.form == Form::ClosedBlend) {
    const bool closed = m.form == Form::ClosedBlend;
    const std::size_t count = closed ? 2 : 4;
    for (std::size_t k = 0; k < count; ++k)
      if (ref.name == (closed ? kClosedNames[k] : kSideNames[k]))
        return {nullptr, &m.curves[k].points, false,
                fmt::format("$.{}.{}.bspline", closed ? "closed-blend" : "blend", ref.name)};
    rd.fail(path, closed ? fmt::format("the closed blend has no curve \"{}\" (its curves: start, "
                                       "end)",
                                       ref.name)
                         : fmt::format("the blend has no curve \"{}\" (its curves: uMin, uMax, "
                                       "vMin, vMax)",
                                       ref.name));
  }
  rd.fail(path, "the net form has no curves: move its control points (move-control-points)");
}

ShapeEdit parseBSplineEdit(std::string_view, const ModelReader& rd, const Json& doc,
                           const BSplinePdeModel& m) {
  // move-control-points
  onlyMembers(rd, doc, {"points", "positions"});
  if (m.form != Form::Net)
    rd.fail("$.op", fmt::format("the {} form has no net of its own: move the points of its "
                                "curves (move-curve-points)",
                                formName(m.form)));
  const Json& list = rd.member(doc, "$", "points");
  rd.expectArray(list, "$.points", 1);
  MoveControlPoints e;
  std::set<std::array<std::uint32_t, 2>> seen;
  for (std::size_t k = 0; k < list.size(); ++k) {
    const std::string path = fmt::format("$.points[{}]", k);
    rd.expectArray(list[k], path, 2);
    if (list[k].size() != 2) rd.fail(path, "expected [i, j]: a row and a column");
    const std::uint32_t i = rd.index(list[k][0], path + "[0]", m.net.nu + 1, "row", "rows");
    const std::uint32_t j = rd.index(list[k][1], path + "[1]", m.net.nv + 1, "column", "columns");
    if (!m.net.given(i, j))
      rd.fail(path, fmt::format("P[{}][{}] is an inner point, solved by the PDE (the given "
                                "points: rows 0, 1, {} and columns 0, 1, {})",
                                i, j, m.net.nu, m.net.nv));
    if (!seen.insert({i, j}).second) rd.fail(path, fmt::format("P[{}][{}] is listed twice", i, j));
    e.points.push_back({i, j});
  }
  e.positions = positionsField(rd, doc, e.points.size());
  return e;
}

void applyBSplineEdit(BSplinePdeModel& m, const SolvedModel&, const ShapeEdit& edit) {
  const auto& e = std::get<MoveControlPoints>(edit);
  for (std::size_t k = 0; k < e.points.size(); ++k)
    m.net(e.points[k][0], e.points[k][1]) = e.positions[k];
}

/// Corners stay shared: every curve end that sat where a moved end of a curve sat (another
/// curve's corner, a closed curve's other end) moves with it.
void keepCornersShared(const BSplinePdeModel& model, BSplinePdeModel& after) {
  BSplinePdeModel before = model;
  const auto was = cornerCurves(before), now = cornerCurves(after);
  std::vector<std::pair<Vec3, Vec3>> moves;  // (where an end was, where it is)
  for (std::size_t c = 0; c < was.size(); ++c)
    for (const bool last : {false, true}) {
      const Vec3& from = last ? was[c]->back() : was[c]->front();
      const Vec3& to = last ? now[c]->back() : now[c]->front();
      if (from != to) moves.emplace_back(from, to);
    }
  for (const auto& [from, to] : moves)
    for (std::size_t c = 0; c < was.size(); ++c)
      for (const bool last : {false, true})
        if ((last ? was[c]->back() : was[c]->front()) == from)
          (last ? now[c]->back() : now[c]->front()) = to;
}

std::vector<Vec3> bsplineReachPoints(const BSplinePdeModel& m) {
  std::vector<Vec3> out;
  for (const Vec3& p : m.net.points)
    if (p.allFinite()) out.push_back(p);  // the inner points are NaN: solved
  BSplinePdeModel copy = m;
  for (std::vector<Vec3>* c : cornerCurves(copy)) out.insert(out.end(), c->begin(), c->end());
  return out;
}

/// Its curves' points (the boundary's sides and second rows, a blend's curves), a tangent
/// row's tips (drawn from the side they leave, at their parameters on it) and a net's given
/// control points (rows 0, 1, n_u and columns 0, 1, n_v).
ModelHandles bsplineHandles(const BSplinePdeModel& m, const SolvedModel&) {
  ModelHandles out;
  const auto named = [&](const char* name, const std::vector<Vec3>& points) {
    addCurve(out, CurveRef{0, name}, name, &points, Vec3::Zero(), false);
  };
  if (m.form == Form::Boundary) {
    const BoundaryInput& b = m.boundary;
    const BoundaryCurve* sides[] = {&b.uMin, &b.uMax, &b.vMin, &b.vMax};
    for (int s = 0; s < 4; ++s) named(kSideNames[s], pointsOf(*sides[s]));
    const SecondRowInput* seconds[] = {&b.uMinSecond, &b.vMinSecond};
    for (int s = 0; s < 2; ++s)
      if (const auto* points = std::get_if<std::vector<Vec3>>(seconds[s]))
        named(kSecondNames[s], *points);
    // A tangent row (x_u along u = 0, x_v along v = 0): drawn from the side it leaves.
    for (int s = 0; s < 2; ++s)
      if (const auto* tangent = std::get_if<TangentCurve>(seconds[s]))
        addTangentRow(out, kSecondNames[s], *tangent, s == 0 ? b.uMin : b.vMin);
  }
  if (m.form == Form::Blend || m.form == Form::ClosedBlend)
    for (std::size_t k = 0; k < m.curves.size(); ++k)
      named(m.form == Form::ClosedBlend ? kClosedNames[k] : kSideNames[k], m.curves[k].points);
  if (m.form == Form::Net)
    for (std::uint32_t i = 0; i <= m.net.nu; ++i)
      for (std::uint32_t j = 0; j <= m.net.nv; ++j)
        if (m.net.given(i, j) && m.net(i, j).allFinite()) {
          ModelHandle& h = out.points.emplace_back();
          h.kind = ModelHandle::Kind::ControlPoint;
          h.index = i;
          h.column = j;
          h.position = m.net(i, j);
        }
  return out;
}

/// No operator to set; its overlay: control nets.
ModelSettings bsplineSettings(const BSplinePdeModel&) { return {{}, {}, "Control nets"}; }

constexpr const char* kOps[] = {"move-control-points"};

}  // namespace

// Corners stay shared after a curve edit (keepCornersShared); no drag advice.
constinit const ShapeEditsOf<BSplinePdeModel> kBSplinePdeEdits = {kOps,
                                                                  bsplineCurve,
                                                                  parseBSplineEdit,
                                                                  applyBSplineEdit,
                                                                  keepCornersShared,
                                                                  bsplineReachPoints,
                                                                  nullptr,
                                                                  bsplineHandles,
                                                                  bsplineSettings};

}  // namespace pdesurf::detail
