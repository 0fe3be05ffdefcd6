// The shape edits of spectral models (spectral/edits.hpp).
#include "methods/spectral/edits.hpp"

#include <limits>

#include <fmt/format.h>

#include "pdesurf/analysis.hpp"

namespace pdesurf {

namespace detail {

namespace {

/// dragAdvice's probe of a spectral patch: point 0 of each position condition given as points
/// moved by this fraction of the surface's size, the patch solved again.
constexpr double kProbeFraction = 1e-3;
/// dragAdvice advises on a spectral patch whose probe moved the surface by more than this many
/// times the probe's offset (twice the aim of locality_test.cpp for a point).
constexpr double kAdviseRatio = 4.0;
/// The spine points a spectral model shows to drag (as `pdesurf spine --count 9` places them).
constexpr std::uint32_t kSpineHandles = 9;

}  // namespace

SetOperator parseSetOperator(const ModelReader& rd, const Json& doc, bool spectral) {
  if (spectral)
    onlyMembers(rd, doc, {"operator", "N", "a", "modes", "remainder"});
  else
    onlyMembers(rd, doc, {"a", "modes", "remainder", "method"});
  SetOperator e;
  if (auto it = doc.find("operator"); it != doc.end())
    e.kind = rd.choice<OperatorKind>(*it, "$.operator",
                                     {{"ugail", OperatorKind::Ugail}, {"fu", OperatorKind::Fu}});
  if (auto it = doc.find("N"); it != doc.end())
    e.power = rd.integer(*it, "$.N", 1, std::numeric_limits<std::uint32_t>::max());
  if (auto it = doc.find("a"); it != doc.end()) e.a = rd.number(*it, "$.a");
  if (auto it = doc.find("modes"); it != doc.end())
    e.modes = rd.integer(*it, "$.modes", 0, std::numeric_limits<std::uint32_t>::max());
  if (auto it = doc.find("remainder"); it != doc.end())
    e.remainder = rd.boolean(*it, "$.remainder");
  if (auto it = doc.find("method"); it != doc.end())
    e.method = rd.choice<ChainMethod>(*it, "$.method",
                                      {{"global", ChainMethod::Global},
                                       {"c2", ChainMethod::ExactC2},
                                       {"shared-curves", ChainMethod::SharedCurves}});
  if (!e.kind && !e.power && !e.a && !e.modes && !e.remainder && !e.method)
    rd.fail("$", spectral ? "set-operator needs \"operator\", \"N\", \"a\", \"modes\" or "
                            "\"remainder\""
                          : "set-operator needs \"a\", \"modes\", \"remainder\" or "
                            "\"method\"");
  return e;
}

const std::vector<Vec3>* curvePoints(const CurveInput& c) {
  const auto* s = std::get_if<SampledCurve>(&c);
  return s ? &s->points : nullptr;
}

Vec3 curveA0(const CurveInput& c) {
  const auto* f = std::get_if<FourierCurve>(&c);
  return f ? f->a0 : Vec3::Zero();
}

void addReachPoints(std::vector<Vec3>& out, const CurveInput& c) {
  if (const auto* s = std::get_if<SampledCurve>(&c))
    out.insert(out.end(), s->points.begin(), s->points.end());
  if (const auto* f = std::get_if<FourierCurve>(&c)) out.push_back(f->a0);
}

namespace {

CurveTarget conditionCurve(SpectralModel& m, const CurveRef& ref, const std::string& path) {
  const ModelReader rd("edit");
  if (!ref.name.empty()) rd.fail(path, "a spectral model's curves are numbered (its conditions)");
  const std::uint32_t i = ref.index;
  if (i >= m.conditions.size())
    rd.fail(path, fmt::format("condition {} is out of range (the model has {}, indices 0 to {})", i,
                              m.conditions.size(), m.conditions.size() - 1));
  return {&m.conditions[i].curve, nullptr, m.conditions[i].derivative > 0,
          fmt::format("$.conditions[{}].curve", i)};
}

ShapeEdit parseSpectralEdit(std::string_view op, const ModelReader& rd, const Json& doc,
                            const SpectralModel&) {
  if (op == "set-operator") return parseSetOperator(rd, doc, true);
  if (op == "move-spine-point") {
    onlyMembers(rd, doc, {"index", "position"});
    MoveSpinePoint e;
    e.index = rd.index(rd.member(doc, "$", "index"), "$.index", kSpineHandles, "spine point",
                       "spine points");
    e.position = rd.vec3(rd.member(doc, "$", "position"), "$.position");
    return e;
  }
  // set-spine: the file's own field, its order and counts checked with the model (the same
  // paths).
  onlyMembers(rd, doc, {"spine"});
  const Json& list = rd.member(doc, "$", "spine");
  rd.expectArray(list, "$.spine", 0);
  SetSpine e;
  for (std::size_t k = 0; k < list.size(); ++k) {
    const std::string path = fmt::format("$.spine[{}]", k);
    rd.expectObject(list[k], path);
    SpineEdit edit;
    const Json& us = rd.member(list[k], path, "u");
    const Json& moved = rd.member(list[k], path, "moved");
    rd.expectArray(us, path + ".u", 1);
    rd.expectArray(moved, path + ".moved", 1);
    for (std::size_t j = 0; j < us.size(); ++j)
      edit.u.push_back(rd.number(us[j], fmt::format("{}.u[{}]", path, j)));
    for (std::size_t j = 0; j < moved.size(); ++j)
      edit.moved.push_back(rd.vec3(moved[j], fmt::format("{}.moved[{}]", path, j)));
    e.edits.push_back(std::move(edit));
  }
  return e;
}

void applySpectralEdit(SpectralModel& m, const SolvedModel& solved, const ShapeEdit& edit) {
  if (const auto* spine = std::get_if<SetSpine>(&edit)) {
    m.spineEdits = spine->edits;
    return;
  }
  if (const auto* point = std::get_if<MoveSpinePoint>(&edit)) {
    // The handles where `solved` has them, the moved one at its position.
    const SpineHandles at = spineHandles(solved, kSpineHandles);
    if (point->index >= at.points.size())
      ModelReader("edit").fail("$.index", "the model has no spine to move");
    std::vector<SpineEdit>& edits = m.spineEdits;
    if (edits.empty() || edits.back().u != at.u) edits.push_back({at.u, at.points});
    edits.back().moved[point->index] = point->position;
    return;
  }
  const auto& e = std::get<SetOperator>(edit);
  SpectralOperator& op = m.op;
  if (e.kind && *e.kind != op.kind) {
    op.kind = *e.kind;
    op.power = op.kind == OperatorKind::Fu ? 3u : op.order() / 2;
  }
  if (e.power) {
    if (op.kind == OperatorKind::Fu)
      ModelReader("edit").fail("$.N", "the Fu operator is of order 6 (N is Ugail's)");
    op.power = *e.power;
  }
  if (e.a) op.a = *e.a;
  if (e.modes) m.options.modes = *e.modes;
  if (e.remainder) m.options.remainder = *e.remainder;
}

std::vector<Vec3> spectralReachPoints(const SpectralModel& m) {
  std::vector<Vec3> out;
  for (const SpectralCondition& c : m.conditions)
    if (c.derivative == 0) addReachPoints(out, c.curve);
  return out;
}

std::string spectralDragAdvice(const SpectralModel& m) {
  // Point 0 of each position condition given as points moved a little, the surface's largest
  // move measured (the probe's meshes correspond vertex by vertex).
  const auto positions = [](const SolvedModel& solved) {
    return tessellate(solved, TessellateOptions{.resolution = kReachSamples}).positions;
  };
  try {
    const SolvedModel base = solve(AnyModel(m), "probe");
    const auto was = positions(base);
    Bounds box;
    for (std::size_t k = 0; k + 2 < was.size(); k += 3)
      box.add(Vec3(was[k], was[k + 1], was[k + 2]));
    const double d = kProbeFraction * box.diagonal();
    double worst = 0.0;
    for (std::size_t i = 0; i < m.conditions.size(); ++i) {
      const auto* points = std::get_if<SampledCurve>(&m.conditions[i].curve);
      if (m.conditions[i].derivative != 0 || !points) continue;
      SpectralModel probe = m;
      std::get<SampledCurve>(probe.conditions[i].curve).points[0] += d * Vec3(1, 2, 3).normalized();
      const auto now = positions(solve(AnyModel(std::move(probe)), "probe"));
      double moved = 0.0;
      for (std::size_t k = 0; k + 2 < was.size(); k += 3)
        moved = std::max(
            moved, Vec3(now[k] - was[k], now[k + 1] - was[k + 1], now[k + 2] - was[k + 2]).norm());
      worst = std::max(worst, moved / d);
    }
    if (worst <= kAdviseRatio) return "";
    return fmt::format(
        "this patch of order {} through {} curves is ill-conditioned between them: one point "
        "moved by d moves the surface by up to {:.2g} d. Move whole curves (their centre marks) "
        "or the spine",
        m.op.order(), m.conditions.size(), worst);
  } catch (const ModelError&) {
    return "";  // a model that does not solve has no drag to advise on
  }
}

/// Its conditions' points, tangent tips (a derivative condition's vectors from the points
/// of the position condition at its u; a Fourier one's a0 from that condition's centre) and
/// spine points (spineHandles, kSpineHandles of them).
ModelHandles spectralHandles(const SpectralModel& m, const SolvedModel& solved) {
  ModelHandles out;
  for (std::uint32_t i = 0; i < m.conditions.size(); ++i) {
    const SpectralCondition& c = m.conditions[i];
    const CurveRef ref{i, ""};
    std::string label = fmt::format("condition {}", i);
    if (c.u) label += fmt::format(" (u = {})", *c.u);
    if (c.derivative) label += fmt::format(", ∂{}u", c.derivative);
    if (c.derivative == 0) {
      addCurve(out, ref, std::move(label), curvePoints(c.curve), curveA0(c.curve), false);
      continue;
    }
    // Vectors, not points: turned and scaled whole; a tangent (∂u) has tips.
    addCurve(out, ref, std::move(label), nullptr, curveA0(c.curve), true);
    if (c.derivative != 1) continue;
    const SpectralCondition* position = nullptr;  // the position condition at the same u
    for (const SpectralCondition& p : m.conditions)
      if (p.derivative == 0 && p.u == c.u) {
        position = &p;
        break;
      }
    if (!position) continue;
    const std::vector<Vec3>* base = curvePoints(position->curve);
    // Its j-th vector drawn from the j-th point of that condition, when it has as many; a
    // Fourier tangent's a0 (its mean over v) from that condition's centre.
    if (const std::vector<Vec3>* at = curvePoints(c.curve)) {
      if (base && base->size() == at->size()) addTangents(out, ref, *at, *base, false);
    } else if (!base || !base->empty()) {
      const Vec3 centre = base ? meanOf(*base) : curveA0(position->curve);
      addTangents(out, ref, {curveA0(c.curve)}, {centre}, true);
    }
  }
  const SpineHandles spine = spineHandles(solved, kSpineHandles);
  for (std::uint32_t k = 0; k < spine.points.size(); ++k) {
    ModelHandle& h = out.points.emplace_back();
    h.kind = ModelHandle::Kind::SpinePoint;
    h.index = k;
    h.position = spine.points[k];
    h.u = spine.u[k];
  }
  return out;
}

/// Its operator: kind, N, a; the modes and remainder it is solved with.
ModelSettings spectralSettings(const SpectralModel& m) {
  return curvesAndSpineSettings({.kind = m.op.kind,
                                 .power = m.op.power,
                                 .a = m.op.a,
                                 .modes = m.options.modes,
                                 .remainder = m.options.remainder});
}

constexpr const char* kOps[] = {"set-operator", "set-spine", "move-spine-point"};

}  // namespace

constinit const ShapeEditsOf<SpectralModel> kSpectralEdits{kOps,
                                                           conditionCurve,
                                                           parseSpectralEdit,
                                                           applySpectralEdit,
                                                           nullptr,
                                                           spectralReachPoints,
                                                           spectralDragAdvice,
                                                           spectralHandles,
                                                           spectralSettings};

}  // namespace detail

SpineHandles spineHandles(const SolvedModel& solved, std::uint32_t count) {
  SpineHandles out;
  const SolvedSpectral* spectral = solved.spectral();
  if (!spectral || !spectral->patch || count < 2) return out;
  const auto [u0, u1] = spectral->range(0);
  for (std::uint32_t i = 0; i < count; ++i) {
    // As `pdesurf spine` places its points (apps/cli/spectral_commands.cpp: spineJson).
    const double u = u0 + (u1 - u0) * static_cast<double>(i) / (count - 1);
    out.u.push_back(u);
    out.points.push_back(spectral->patch->spine(u));
  }
  return out;
}

}  // namespace pdesurf
