// B-spline PDE models solved and tessellated (include/pdesurf/bspline_pde_model.hpp).
#include <algorithm>
#include <stdexcept>

#include "bspline_pde/internal.hpp"
#include "pdesurf/bspline_pde_model.hpp"
#include "pdesurf/error.hpp"

namespace pdesurf {

namespace {

/// Which part of the file an engine error belongs to.
std::string formPath(BSplinePdeModel::Form form) {
  const std::string name = formName(form);
  return name.find('-') == std::string::npos ? "$." + name : "$[\"" + name + "\"]";
}

}  // namespace

const char* formName(BSplinePdeModel::Form form) {
  switch (form) {
    case BSplinePdeModel::Form::Net:
      return "net";
    case BSplinePdeModel::Form::Boundary:
      return "boundary";
    case BSplinePdeModel::Form::Blend:
      return "blend";
    case BSplinePdeModel::Form::ClosedBlend:
      return "closed-blend";
  }
  return "?";
}

BSplineBoundary boundaryOf(const BoundaryInput& in, const BSplinePdeOptions& knots) {
  BSplineBoundary b;
  b.nu = in.nu;
  b.nv = in.nv;
  b.knots = knots;
  b.uMin = in.uMin;
  b.uMax = in.uMax;
  b.vMin = in.vMin;
  b.vMax = in.vMax;
  const auto second = [](const SecondRowInput& row) -> SecondRow {
    if (const auto* given = std::get_if<std::vector<Vec3>>(&row)) return *given;
    const BoundaryCurve& c = std::get<TangentCurve>(row).vectors;
    if (const auto* s = std::get_if<BSplineCurve>(&c))
      return TangentFunction([s = *s](double t) { return s.evaluate(t); });
    CurveSamples samples = std::get<CurveSamples>(c);
    const std::size_t count = samples.points.size();
    if (samples.t.empty())  // vectors have no chord length: uniform parameters
      for (std::size_t k = 0; k < count; ++k)
        samples.t.push_back(static_cast<double>(k) / static_cast<double>(count - 1));
    return TangentFunction([s = std::move(samples)](double t) {
      const auto k = static_cast<std::size_t>(
          std::clamp<std::ptrdiff_t>(std::upper_bound(s.t.begin(), s.t.end(), t) - s.t.begin(), 1,
                                     static_cast<std::ptrdiff_t>(s.t.size()) - 1));
      const double w = (t - s.t[k - 1]) / (s.t[k] - s.t[k - 1]);
      return Vec3((1.0 - w) * s.points[k - 1] + w * s.points[k]);
    });
  };
  b.uMinSecond = second(in.uMinSecond);
  b.vMinSecond = second(in.vMinSecond);
  return b;
}

SolvedBSplinePde solve(const BSplinePdeModel& m, const std::string& source) {
  SolvedBSplinePde s;
  try {
    switch (m.form) {
      case BSplinePdeModel::Form::Net:
        s.pieces.push_back(solve(m.net, m.knots));
        break;
      case BSplinePdeModel::Form::Boundary:
        s.pieces.push_back(solve(boundaryNet(boundaryOf(m.boundary, m.knots)), m.knots));
        break;
      case BSplinePdeModel::Form::Blend:
      case BSplinePdeModel::Form::ClosedBlend: {
        C1Blend blend =
            m.form == BSplinePdeModel::Form::Blend
                ? blendFourCurves(m.curves[0], m.curves[1], m.curves[2], m.curves[3], m.blendN)
                : blendClosedCurves(m.curves[0], m.curves[1], m.blendN);
        s.pieces = std::move(blend.pieces);
        s.origin = std::move(blend.origin);
        s.closedV = blend.closedV;
        s.constraintResidual = blend.maxConstraintResidual;
        s.c1Gap = blend.maxC1Gap;
        s.seamGaps = std::move(blend.seamGaps);
        return s;
      }
    }
  } catch (const InvalidArgument& e) {
    throw ModelError(source, formPath(m.form), e.what());
  }
  s.origin.push_back({0, 0});
  return s;
}

Mesh tessellate(const SolvedBSplinePde& solved, const TessellateOptions& options) {
  checkTessellateOptions(options);
  const BSplineSurface& first = solved.pieces.front();
  const std::uint32_t segments = bspline::segmentsPerSpan(first, options.resolution);
  if (solved.pieces.size() == 1 && !solved.closedV)
    return bspline::tessellateSpans(first, segments);

  // One grid over the pieces' unit squares; a seam point is the first piece's.
  std::uint32_t pu = 0, pv = 0;
  for (const auto& o : solved.origin) {
    pu = std::max(pu, o[0] + 1);
    pv = std::max(pv, o[1] + 1);
  }
  const std::uint32_t cu = first.uSpans() * segments, cv = first.vSpans() * segments;
  const std::uint32_t rows = pu * cu + 1, cols = pv * cv + (solved.closedV ? 0 : 1);
  Mesh mesh;
  mesh.positions.assign(3 * std::size_t{rows} * cols, 0.0f);
  mesh.normals.assign(3 * std::size_t{rows} * cols, 0.0f);
  std::vector<std::uint8_t> written(std::size_t{rows} * cols, 0);
  for (std::size_t k = 0; k < solved.pieces.size(); ++k) {
    const Mesh piece = bspline::tessellateSpans(solved.pieces[k], segments);
    const auto [p, q] = solved.origin[k];
    for (std::uint32_t a = 0; a <= cu; ++a)
      for (std::uint32_t b = 0; b <= cv; ++b) {
        const std::size_t g = std::size_t{p * cu + a} * cols + (q * cv + b) % cols;
        if (written[g]) continue;
        written[g] = 1;
        const std::size_t l = std::size_t{a} * (cv + 1) + b;
        for (int c = 0; c < 3; ++c) {
          mesh.positions[3 * g + c] = piece.positions[3 * l + c];
          mesh.normals[3 * g + c] = piece.normals[3 * l + c];
        }
      }
  }
  for (std::size_t k = 0; k < solved.pieces.size(); ++k) {
    const auto [p, q] = solved.origin[k];
    const auto piece = static_cast<std::uint32_t>(k);
    for (std::uint32_t a = p * cu; a < (p + 1) * cu; ++a)
      for (std::uint32_t b = q * cv; b < (q + 1) * cv; ++b) {
        const std::uint32_t b1 = (b + 1) % cols;  // the closed blend's last column is column 0
        const std::uint32_t v00 = a * cols + b, v10 = v00 + cols;
        const std::uint32_t v01 = a * cols + b1, v11 = v01 + cols;
        mesh.indices.insert(mesh.indices.end(), {v00, v10, v11, v00, v11, v01});
        mesh.patchIds.insert(mesh.patchIds.end(), {piece, piece});
      }
  }
  return mesh;
}

}  // namespace pdesurf
