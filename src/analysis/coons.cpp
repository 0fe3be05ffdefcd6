// Bilinear and bicubic Coons patches (seed 000 §4.2; Coons 1967): docs/coons.md.
#include "pdesurf/coons.hpp"
#include "pdesurf/error.hpp"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <utility>

namespace pdesurf {

namespace {

/// Cubic Hermite basis on [0, 1] and its derivative: H0, H1 (values at 0 and 1), H2, H3
/// (derivatives at 0 and 1).
std::array<double, 4> hermite(double t) {
  const double t2 = t * t, t3 = t2 * t;
  return {1 - 3 * t2 + 2 * t3, 3 * t2 - 2 * t3, t - 2 * t2 + t3, t3 - t2};
}
std::array<double, 4> hermiteDerivative(double t) {
  const double t2 = t * t;
  return {-6 * t + 6 * t2, 6 * t - 6 * t2, 1 - 4 * t + 3 * t2, 3 * t2 - 2 * t};
}
/// Linear blending: 1 - t and t (the bilinear patch), with derivatives -1 and 1.
std::array<double, 4> linear(double t) { return {1 - t, t, 0, 0}; }
std::array<double, 4> linearDerivative(double) { return {-1, 1, 0, 0}; }

CoonsCurve componentProduct(const Vec3& w, const CoonsCurve& c) {
  return {[w, f = c.value](double t) -> Vec3 { return w.cwiseProduct(f(t)); },
          [w, f = c.derivative](double t) -> Vec3 { return w.cwiseProduct(f(t)); }};
}

}  // namespace

CoonsPatch CoonsPatch::bilinear(CoonsBoundary boundary) {
  CoonsPatch p;
  p.b_ = std::move(boundary);
  p.bicubic_ = false;
  p.corner_[0] = {p.b_.alpha.value(0), p.b_.beta.value(0), Vec3::Zero(), Vec3::Zero()};
  p.corner_[1] = {p.b_.alpha.value(1), p.b_.beta.value(1), Vec3::Zero(), Vec3::Zero()};
  return p;
}

CoonsPatch CoonsPatch::bicubic(CoonsBoundary boundary, CoonsTangents tangents) {
  CoonsPatch p;
  p.b_ = std::move(boundary);
  p.t_ = std::move(tangents);
  p.bicubic_ = true;
  const CoonsBoundary& b = p.b_;
  const CoonsTangents& t = p.t_;
  // Positions and the derivatives each loft carries across its own boundaries: on v = 0
  // the u-loft's data (γ, δ, Tγ, Tδ at v = 0) cancel exactly, on u = 0 the v-loft's.
  p.corner_[0] = {b.alpha.value(0), b.beta.value(0), t.alpha.value(0), t.beta.value(0)};
  p.corner_[1] = {b.alpha.value(1), b.beta.value(1), t.alpha.value(1), t.beta.value(1)};
  p.corner_[2] = {t.gamma.value(0), t.gamma.value(1),
                  0.5 * (t.alpha.derivative(0) + t.gamma.derivative(0)),
                  0.5 * (t.beta.derivative(0) + t.gamma.derivative(1))};
  p.corner_[3] = {t.delta.value(0), t.delta.value(1),
                  0.5 * (t.alpha.derivative(1) + t.delta.derivative(0)),
                  0.5 * (t.beta.derivative(1) + t.delta.derivative(1))};
  return p;
}

SurfacePoint CoonsPatch::evaluate(double u, double v) const {
  const auto hu = bicubic_ ? hermite(u) : linear(u), hv = bicubic_ ? hermite(v) : linear(v);
  const auto du = bicubic_ ? hermiteDerivative(u) : linearDerivative(u);
  const auto dv = bicubic_ ? hermiteDerivative(v) : linearDerivative(v);
  // The u-loft (through γ and δ) and the v-loft (through α and β).
  std::array<Vec3, 4> uData = {b_.gamma.value(v), b_.delta.value(v), Vec3::Zero(), Vec3::Zero()};
  std::array<Vec3, 4> uDataV = {b_.gamma.derivative(v), b_.delta.derivative(v), Vec3::Zero(),
                                Vec3::Zero()};
  std::array<Vec3, 4> vData = {b_.alpha.value(u), b_.beta.value(u), Vec3::Zero(), Vec3::Zero()};
  std::array<Vec3, 4> vDataU = {b_.alpha.derivative(u), b_.beta.derivative(u), Vec3::Zero(),
                                Vec3::Zero()};
  if (bicubic_) {
    uData[2] = t_.gamma.value(v);
    uData[3] = t_.delta.value(v);
    uDataV[2] = t_.gamma.derivative(v);
    uDataV[3] = t_.delta.derivative(v);
    vData[2] = t_.alpha.value(u);
    vData[3] = t_.beta.value(u);
    vDataU[2] = t_.alpha.derivative(u);
    vDataU[3] = t_.beta.derivative(u);
  }
  SurfacePoint s{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  for (int i = 0; i < 4; ++i) {
    s.p += hu[i] * uData[i] + hv[i] * vData[i];
    s.du += du[i] * uData[i] + hv[i] * vDataU[i];
    s.dv += hu[i] * uDataV[i] + dv[i] * vData[i];
    for (int j = 0; j < 4; ++j) {
      s.p -= hu[i] * hv[j] * corner_[i][j];
      s.du -= du[i] * hv[j] * corner_[i][j];
      s.dv -= hu[i] * dv[j] * corner_[i][j];
    }
  }
  return s;
}

CoonsBoundary boundaryOf(const VertexFramePatch& source) {
  // S(u, v0) and its u-derivative; S(u0, v) and its v-derivative. The curves share one
  // copy of the patch, so they outlive the argument.
  auto patch = std::make_shared<const VertexFramePatch>(source);
  auto along = [patch](bool inU, double fixed) {
    return CoonsCurve{[patch, inU, fixed](double t) {
                        return inU ? patch->position(t, fixed) : patch->position(fixed, t);
                      },
                      [patch, inU, fixed](double t) {
                        return inU ? patch->evaluate(t, fixed).du : patch->evaluate(fixed, t).dv;
                      }};
  };
  return {along(true, 0), along(true, 1), along(false, 0), along(false, 1)};
}

CoonsTangents seedTangents(const CoonsBoundary& boundary, const std::array<Vec3, 4>& w) {
  return {componentProduct(w[0], boundary.alpha), componentProduct(w[1], boundary.beta),
          componentProduct(w[2], boundary.gamma), componentProduct(w[3], boundary.delta)};
}

CoonsTangents patchTangents(const VertexFramePatch& source) {
  // S_v along v = v0 (in u) or S_u along u = u0 (in v); the derivative along the boundary
  // by central differences (one-sided at the ends, still second order).
  auto patch = std::make_shared<const VertexFramePatch>(source);
  auto cross = [patch](bool inU, double fixed) {
    auto value = [patch, inU, fixed](double t) -> Vec3 {
      return inU ? patch->evaluate(t, fixed).dv : patch->evaluate(fixed, t).du;
    };
    auto derivative = [value](double t) -> Vec3 {
      const double h = kCoonsTangentStep;
      if (t - h < 0) return (-3 * value(t) + 4 * value(t + h) - value(t + 2 * h)) / (2 * h);
      if (t + h > 1) return (3 * value(t) - 4 * value(t - h) + value(t - 2 * h)) / (2 * h);
      return (value(t + h) - value(t - h)) / (2 * h);
    };
    return CoonsCurve{value, derivative};
  };
  return {cross(true, 0), cross(true, 1), cross(false, 0), cross(false, 1)};
}

Mesh tessellate(const std::vector<CoonsPatch>& patches, const TessellateOptions& options) {
  checkTessellateOptions(options);
  const std::uint32_t n = options.resolution;
  Mesh mesh;
  for (std::size_t k = 0; k < patches.size(); ++k) {
    const auto base = static_cast<std::uint32_t>(mesh.vertexCount());
    for (std::uint32_t j = 0; j < n; ++j)
      for (std::uint32_t i = 0; i < n; ++i) {
        const SurfacePoint s = patches[k].evaluate(double(i) / (n - 1), double(j) / (n - 1));
        Vec3 normal = s.du.cross(s.dv);
        const double length = normal.norm();
        normal = length > 0 ? Vec3(normal / length) : Vec3(0, 0, 1);
        for (int c = 0; c < 3; ++c) {
          mesh.positions.push_back(static_cast<float>(s.p[c]));
          mesh.normals.push_back(static_cast<float>(normal[c]));
        }
      }
    for (std::uint32_t j = 0; j + 1 < n; ++j)
      for (std::uint32_t i = 0; i + 1 < n; ++i) {
        const std::uint32_t a = base + j * n + i, b = a + 1, c = a + n + 1, d = a + n;
        mesh.indices.insert(mesh.indices.end(), {a, b, c, a, c, d});
        mesh.patchIds.insert(mesh.patchIds.end(), 2, static_cast<std::uint32_t>(k));
      }
  }
  return mesh;
}

}  // namespace pdesurf
