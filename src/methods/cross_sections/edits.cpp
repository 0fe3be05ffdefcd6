// The shape edits of cross-section chains (cross_sections/edits.hpp).
#include "methods/cross_sections/edits.hpp"

#include <algorithm>
#include <numbers>

#include <fmt/format.h>

#include "methods/spectral/edits.hpp"
#include "pdesurf/spectral_io.hpp"

namespace pdesurf::detail {

namespace {

/// The points of a closed curve of a chain, sampled on its solved surface at chain parameter
/// `s`: `count` points at uniform v, with their v.
SampledCurve sectionAt(const CrossSectionChain& chain, double s, std::uint32_t count) {
  const ChainPatch* at = &chain.patches.front();
  for (const ChainPatch& p : chain.patches)
    if (chain.curveU[p.shownFirstCurve] <= s && s <= chain.curveU[p.shownLastCurve]) {
      at = &p;
      break;
    }
  const double t = (s - chain.curveU[at->firstCurve]) / at->length;
  SampledCurve out;
  for (std::uint32_t j = 0; j < count; ++j) {
    const double v = 2.0 * std::numbers::pi * j / count;
    out.points.push_back(at->patch.position(t, v));
    out.v.push_back(v);
  }
  return out;
}

/// The number of points a curve holds (Fourier curves: 0).
std::size_t pointCount(const CurveInput& c) {
  const std::vector<Vec3>* points = curvePoints(c);
  return points ? points->size() : 0;
}

CurveTarget sectionCurve(CrossSectionModel& m, const CurveRef& ref, const std::string& path) {
  const ModelReader rd("edit");
  if (!ref.name.empty()) rd.fail(path, "a chain's sections are numbered");
  if (ref.index >= m.curves.size())
    rd.fail(path, fmt::format("section {} is out of range (the chain has {}, indices 0 to {})",
                              ref.index, m.curves.size(), m.curves.size() - 1));
  return {&m.curves[ref.index], nullptr, false, fmt::format("$.curves[{}]", ref.index)};
}

ShapeEdit parseSectionEdit(std::string_view op, const ModelReader& rd, const Json& doc,
                           const CrossSectionModel& m) {
  if (op == "set-operator") return parseSetOperator(rd, doc, false);
  const std::size_t count = m.curves.size();
  if (op == "remove-section") {
    onlyMembers(rd, doc, {"index"});
    return RemoveSection{
        rd.index(rd.member(doc, "$", "index"), "$.index", count, "section", "sections")};
  }
  onlyMembers(rd, doc, {"index", "curve"});
  AddSection e;
  e.index =
      rd.integer(rd.member(doc, "$", "index"), "$.index", 0, static_cast<std::uint32_t>(count));
  if (auto it = doc.find("curve"); it != doc.end())
    e.curve = parseCurve(it->dump(), "edit", "$.curve");
  else if (e.index == 0 || e.index == count)
    rd.fail("$.curve",
            "a section before the first or after the last needs its \"curve\" "
            "(between two sections it is sampled from the surface)");
  return e;
}

void applySectionEdit(CrossSectionModel& m, const SolvedModel& solved, const ShapeEdit& edit) {
  if (const auto* op = std::get_if<SetOperator>(&edit)) {
    CrossSectionOptions& options = m.options;
    if (op->a) options.a = *op->a;
    if (op->modes) options.modes = *op->modes;
    if (op->remainder) options.remainder = *op->remainder;
    if (op->method) options.method = *op->method;
  } else if (const auto* add = std::get_if<AddSection>(&edit)) {
    const std::size_t i = add->index;
    CurveInput curve;
    if (add->curve) {
      curve = *add->curve;
    } else {
      const CrossSectionChain& chain = *solved.spectral()->chain;
      const std::size_t count =
          std::max<std::size_t>({2 * std::size_t{m.options.modes} + 1, pointCount(m.curves[i - 1]),
                                 pointCount(m.curves[i]), kMinSampledSection});
      curve = sectionAt(chain, 0.5 * (chain.curveU[i - 1] + chain.curveU[i]),
                        static_cast<std::uint32_t>(count));
    }
    m.curves.insert(m.curves.begin() + static_cast<std::ptrdiff_t>(i), std::move(curve));
    if (std::vector<double>& u = m.options.u; !u.empty()) {
      const double at = i == 0          ? u[0] - (u[1] - u[0])
                        : i == u.size() ? u.back() + (u.back() - u[u.size() - 2])
                                        : 0.5 * (u[i - 1] + u[i]);
      u.insert(u.begin() + static_cast<std::ptrdiff_t>(i), at);
    }
  } else {
    const std::uint32_t index = std::get<RemoveSection>(edit).index;
    m.curves.erase(m.curves.begin() + index);
    if (!m.options.u.empty()) m.options.u.erase(m.options.u.begin() + index);
  }
}

std::vector<Vec3> sectionReachPoints(const CrossSectionModel& m) {
  std::vector<Vec3> out;
  for (const CurveInput& c : m.curves) addReachPoints(out, c);
  return out;
}

/// The seed's marching chains ("c2", "shared-curves") pass a moved point on.
std::string sectionDragAdvice(const CrossSectionModel& m) {
  if (m.options.method == ChainMethod::Global) return "";
  return fmt::format(
      "this chain is built by the seed's marching method \"{}\": a moved point is passed "
      "on from patch to patch and can move the surface far from it. The global chain keeps a "
      "drag local",
      m.options.method == ChainMethod::ExactC2 ? "c2" : "shared-curves");
}

/// Its sections' points.
ModelHandles sectionHandles(const CrossSectionModel& m, const SolvedModel&) {
  ModelHandles out;
  for (std::uint32_t i = 0; i < m.curves.size(); ++i)
    addCurve(out, CurveRef{i, ""}, fmt::format("section {}", i), curvePoints(m.curves[i]),
             curveA0(m.curves[i]), false);
  return out;
}

/// Its chain's a, modes, remainder and method.
ModelSettings sectionSettings(const CrossSectionModel& m) {
  const CrossSectionOptions& o = m.options;
  return curvesAndSpineSettings(
      {.a = o.a, .modes = o.modes, .remainder = o.remainder, .method = o.method});
}

constexpr const char* kOps[] = {"set-operator", "add-section", "remove-section"};

}  // namespace

constinit const ShapeEditsOf<CrossSectionModel> kCrossSectionEdits{
    kOps,           sectionCurve,       parseSectionEdit,  applySectionEdit,
    nullptr,        sectionReachPoints, sectionDragAdvice, sectionHandles,
    sectionSettings};

}  // namespace pdesurf::detail
