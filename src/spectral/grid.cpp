// Grid evaluation with per-u and per-v tables, and watertight tessellation.
#include "numerics/eigen_warnings.hpp"  // first: see the file

#include <algorithm>
#include <cmath>
#include <numbers>
#include <type_traits>

#include "spectral/internal.hpp"

namespace pdesurf {

namespace {
constexpr double kTwoPi = 2.0 * std::numbers::pi;
}

void evaluateGrid(const SpectralPatch& patch, std::span<const double> us,
                  std::span<const double> vs, SpectralGrid& out) {
  const std::size_t nu = us.size(), nv = vs.size();
  const std::uint32_t modes = patch.modes();
  const double length = patch.uEnd() - patch.uStart();
  out.uCount = nu;
  out.vCount = nv;
  out.p.assign(nu * nv, Vec3::Zero());
  out.du.assign(nu * nv, Vec3::Zero());
  out.dv.assign(nu * nv, Vec3::Zero());
  // The mode sums for all points are one matrix product T · K: T (per v) holds cos nv and
  // sin nv, K (per u) holds, for p, S_u and S_v, the mode functions that multiply them.
  // Plain buffers (no Eigen heap types of double: see SmallMatrix in basis.hpp).
  const std::size_t m1 = modes + 1;
  std::vector<double> trig(nv * 2 * m1);  // trig[j][n]: cos, then sin
  for (std::size_t j = 0; j < nv; ++j)
    for (std::size_t n = 0; n < m1; ++n) {
      trig[j * 2 * m1 + n] = std::cos(static_cast<double>(n) * vs[j]);
      trig[j * 2 * m1 + m1 + n] = std::sin(static_cast<double>(n) * vs[j]);
    }
  const std::size_t width = 9 * nu;
  std::vector<double> modeTableData(2 * m1 * width, 0.0);  // [row n][9 i + quantity]
  auto modeTable = [&](std::size_t row, std::size_t col) -> double& {
    return modeTableData[row * width + col];
  };
  const double inv = 1.0 / length;
  // Mode functions at every u, in the precision the mode needs (basis.hpp).
  auto fill = [&](auto precision, std::uint32_t n) {
    using T = decltype(precision);
    const spectral::ModeBasis& basis = (*patch.bases_)[n];
    const SpectralPatch::ModeCoefficients& coef = patch.coefficients_[n];
    const auto cosine = spectral::coefficientMatrix<T>(coef.cosine, coef.cosineLow);
    const auto sine = spectral::coefficientMatrix<T>(coef.sine, coef.sineLow);
    std::conditional_t<
        std::is_same_v<T, double>, spectral::SmallMatrix,
        std::conditional_t<std::is_same_v<T, spectral::Quad>, spectral::MatrixQ, spectral::MatrixR>>
        table;
    const double nd = n;
    for (std::size_t i = 0; i < nu; ++i) {
      basis.evaluate((us[i] - patch.uStart()) * inv, 1, table);
      T acc[2][6] = {};
      for (Eigen::Index q = 0; q < table.cols(); ++q)
        for (int r = 0; r < 2; ++r) {
          const T f = table(r, q);
          for (int d = 0; d < 3; ++d) {
            acc[r][d] += f * cosine(q, d);
            acc[r][3 + d] += f * sine(q, d);
          }
        }
      const std::size_t c0 = 9 * i;
      for (std::size_t d = 0; d < 3; ++d) {
        const double a0 = static_cast<double>(acc[0][d]), a1 = static_cast<double>(acc[1][d]);
        const double b0 = static_cast<double>(acc[0][3 + d]),
                     b1 = static_cast<double>(acc[1][3 + d]);
        modeTable(n, c0 + d) = a0;
        modeTable(m1 + n, c0 + d) = b0;
        modeTable(n, c0 + 3 + d) = inv * a1;
        modeTable(m1 + n, c0 + 3 + d) = inv * b1;
        modeTable(n, c0 + 6 + d) = nd * b0;
        modeTable(m1 + n, c0 + 6 + d) = -nd * a0;
      }
    }
  };
  for (std::uint32_t n = 0; n <= modes; ++n) {
    switch (patch.coefficients_[n].precision) {
      case ModePrecision::Double:
        fill(0.0, n);
        break;
      case ModePrecision::Extended:
        fill(spectral::Real(0), n);
        break;
      case ModePrecision::Quad:
        fill(spectral::Quad(0), n);
        break;
    }
  }
  std::vector<double> sums(nv * width, 0.0);  // [j][9 i + quantity] = Σ_r trig[j][r] K[r][.]
  for (std::size_t j = 0; j < nv; ++j)
    for (std::size_t r = 0; r < 2 * m1; ++r) {
      const double f = trig[j * 2 * m1 + r];
      const double* row = &modeTableData[r * width];
      double* dst = &sums[j * width];
      for (std::size_t c = 0; c < width; ++c) dst[c] += f * row[c];
    }
  for (std::size_t i = 0; i < nu; ++i) {
    Vec3 spine = Vec3::Zero(), spineD = Vec3::Zero();
    for (const SpineOffset& s : patch.spineOffsets_) {
      spine += spectral::evaluateNaturalSpline(s, us[i], 0);
      spineD += spectral::evaluateNaturalSpline(s, us[i], 1);
    }
    for (std::size_t j = 0; j < nv; ++j) {
      const double* q = &sums[j * width + 9 * i];
      out.p[i * nv + j] = Vec3(q[0], q[1], q[2]) + spine;
      out.du[i * nv + j] = Vec3(q[3], q[4], q[5]) + spineD;
      out.dv[i * nv + j] = Vec3(q[6], q[7], q[8]);
    }
  }
  if (patch.tail_) {
    // R = Σ ψ_i(t) d_i(v): ψ per u, d per v.
    const auto& tail = *patch.tail_;
    const std::size_t order = tail.terms.size();
    std::vector<std::size_t> active;
    for (std::size_t k = 0; k < order; ++k)
      if (!tail.terms[k].empty()) active.push_back(k);
    std::vector<Vec3> d(nv * active.size()), dd(nv * active.size());
    for (std::size_t j = 0; j < nv; ++j)
      for (std::size_t q = 0; q < active.size(); ++q) {
        d[j * active.size() + q] = tail.difference(active[q], vs[j], 0);
        dd[j * active.size() + q] = tail.difference(active[q], vs[j], 1);
      }
    for (std::size_t i = 0; i < nu; ++i) {
      const spectral::MatrixR psi = tail.psi((us[i] - patch.uStart()) * inv, 0, 1);  // 2 × order
      for (std::size_t j = 0; j < nv; ++j)
        for (std::size_t q = 0; q < active.size(); ++q) {
          const auto k = static_cast<Eigen::Index>(active[q]);
          const double p0 = static_cast<double>(psi(0, k)), p1 = static_cast<double>(psi(1, k));
          out.p[i * nv + j] += p0 * d[j * active.size() + q];
          out.du[i * nv + j] += inv * p1 * d[j * active.size() + q];
          out.dv[i * nv + j] += p0 * dd[j * active.size() + q];
        }
    }
  }
}

SpectralGrid evaluateGrid(const SpectralPatch& patch, std::span<const double> us,
                          std::span<const double> vs) {
  SpectralGrid g;
  evaluateGrid(patch, us, vs, g);
  return g;
}

namespace {

struct Piece {
  const SpectralPatch* patch;
  double tStart, tEnd;
};

/// Tessellates consecutive pieces of a chain (one piece for a lone patch): the last row of
/// a piece and the first row of the next are one row of vertices.
Mesh tessellatePieces(const std::vector<Piece>& pieces, const TessellateOptions& options) {
  checkTessellateOptions(options);
  const std::uint32_t rowsPer = options.resolution;
  // TessellateOptions::aroundResolution: 0 asks for 4 (rows − 1) columns, at least 8.
  const std::uint32_t cols =
      options.aroundResolution != 0 ? options.aroundResolution : std::max(4 * (rowsPer - 1), 8u);
  std::vector<double> vs(cols);
  for (std::uint32_t j = 0; j < cols; ++j) vs[j] = kTwoPi * j / cols;
  // Evaluate every piece; global rows: piece p row r → p·(rowsPer-1) + r.
  const std::size_t rows = pieces.size() * (rowsPer - 1) + 1;
  std::vector<Vec3> pos(rows * cols, Vec3::Zero()), nrm(rows * cols, Vec3::Zero()),
      spineAt(rows * cols, Vec3::Zero());
  std::vector<int> hits(rows * cols, 0);
  SpectralGrid grid;
  double extent = 0.0;
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    const SpectralPatch& patch = *pieces[p].patch;
    std::vector<double> us(rowsPer);
    for (std::uint32_t r = 0; r < rowsPer; ++r) {
      const double t = pieces[p].tStart + (pieces[p].tEnd - pieces[p].tStart) * r / (rowsPer - 1);
      us[r] = patch.uStart() + t * (patch.uEnd() - patch.uStart());
    }
    evaluateGrid(patch, us, vs, grid);
    for (std::uint32_t r = 0; r < rowsPer; ++r) {
      const Vec3 spine = patch.spine(us[r]);
      for (std::uint32_t j = 0; j < cols; ++j) {
        const std::size_t g = (p * (rowsPer - 1) + r) * cols + j;
        const std::size_t k = r * cols + j;
        pos[g] += grid.p[k];
        nrm[g] += grid.du[k].cross(grid.dv[k]);
        spineAt[g] += spine;
        hits[g] += 1;
        lo = lo.cwiseMin(grid.p[k]);
        hi = hi.cwiseMax(grid.p[k]);
      }
    }
  }
  extent = (hi - lo).norm();
  const double degenerate = kDegenerateNormalTolerance * std::max(extent * extent, 1e-300);
  double orientation = 0.0;
  for (std::size_t g = 0; g < pos.size(); ++g) {
    pos[g] /= hits[g];
    spineAt[g] /= hits[g];
    orientation += nrm[g].dot(pos[g] - spineAt[g]);
  }
  const bool flip = orientation < 0.0;  // normals face away from the spine
  // Vertex ids: a row whose points all coincide is one vertex.
  std::vector<std::uint32_t> id(rows * cols);
  std::vector<Vec3> vpos, vnrm;
  std::vector<char> vbad;
  for (std::size_t r = 0; r < rows; ++r) {
    double spreadRow = 0.0;
    for (std::uint32_t j = 0; j < cols; ++j)
      spreadRow = std::max(spreadRow, (pos[r * cols + j] - pos[r * cols]).norm());
    const bool collapsed = spreadRow <= kDegenerateCurveTolerance * std::max(extent, 1e-300);
    for (std::uint32_t j = 0; j < cols; ++j) {
      const std::size_t g = r * cols + j;
      Vec3 n = flip ? Vec3(-nrm[g]) : nrm[g];
      const bool bad = collapsed || n.norm() <= degenerate * hits[g];
      if (collapsed && j > 0) {
        id[g] = id[r * cols];
        continue;
      }
      id[g] = static_cast<std::uint32_t>(vpos.size());
      vpos.push_back(pos[g]);
      vnrm.push_back(bad ? Vec3::Zero() : Vec3(n.normalized()));
      vbad.push_back(bad ? 1 : 0);
    }
  }
  Mesh mesh;
  std::vector<Vec3> faceSum(vpos.size(), Vec3::Zero());
  auto addTri = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t patchId) {
    if (a == b || b == c || a == c) return;
    if (flip) std::swap(b, c);
    mesh.indices.insert(mesh.indices.end(), {a, b, c});
    mesh.patchIds.push_back(patchId);
    const Vec3 fn = (vpos[b] - vpos[a]).cross(vpos[c] - vpos[a]);
    faceSum[a] += fn;
    faceSum[b] += fn;
    faceSum[c] += fn;
  };
  for (std::size_t r = 0; r + 1 < rows; ++r) {
    const auto patchId = static_cast<std::uint32_t>(r / (rowsPer - 1));
    for (std::uint32_t j = 0; j < cols; ++j) {
      const std::uint32_t j1 = (j + 1) % cols;
      const std::uint32_t a = id[r * cols + j], b = id[r * cols + j1], c = id[(r + 1) * cols + j],
                          d = id[(r + 1) * cols + j1];
      // Counter-clockwise in (u, v) is counter-clockwise seen from S_u × S_v.
      addTri(a, c, d, patchId);
      addTri(a, d, b, patchId);
    }
  }
  for (std::size_t k = 0; k < vpos.size(); ++k) {
    if (vbad[k]) {
      // Collapsed rows and poles: the area-weighted normal of the faces around the vertex.
      const double len = faceSum[k].norm();
      vnrm[k] = len > 0.0 ? Vec3(faceSum[k] / len) : Vec3::UnitZ();
    }
    for (int c = 0; c < 3; ++c) {
      mesh.positions.push_back(static_cast<float>(vpos[k][c]));
      mesh.normals.push_back(static_cast<float>(vnrm[k][c]));
    }
  }
  return mesh;
}

}  // namespace

Mesh tessellate(const SpectralPatch& patch, const TessellateOptions& options) {
  return tessellatePieces({Piece{&patch, 0.0, 1.0}}, options);
}

Mesh tessellate(const CrossSectionChain& chain, const TessellateOptions& options) {
  std::vector<Piece> pieces;
  for (const ChainPatch& p : chain.patches) pieces.push_back({&p.patch, p.tStart, p.tEnd});
  return tessellatePieces(pieces, options);
}

}  // namespace pdesurf
