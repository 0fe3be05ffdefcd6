// STEP and IGES round trips: the files pdesurf writes, read back by Open CASCADE's own
// readers, their faces' surfaces evaluated and compared with pdesurf's patches.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>

#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_Surface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Reader.hxx>
#include <STEPControl_Reader.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <gp_Pnt.hxx>

#include "pdesurf/analysis.hpp"
#include "pdesurf/cad_export.hpp"
#include "pdesurf/nurbs.hpp"
#include "pdesurf/occt_convert.hpp"
#include "pdesurf/spectral_io.hpp"
#include "support/cli_run.hpp"
#include "support/examples.hpp"
#include "support/models.hpp"

namespace pdesurf {
namespace {

/// Samples per side of the grid each read-back face is compared on.
constexpr int kGrid = 13;

using testing::example;

Vec3 toVec(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }

/// The faces of a STEP or IGES file, read by Open CASCADE.
std::vector<TopoDS_Face> readFaces(const std::string& path, CadFormat format,
                                   TopoDS_Shape* shapeOut = nullptr) {
  TopoDS_Shape shape;
  if (format == CadFormat::Step) {
    STEPControl_Reader reader;
    EXPECT_EQ(reader.ReadFile(path.c_str()), IFSelect_RetDone) << path;
    reader.TransferRoots();
    shape = reader.OneShape();
  } else {
    IGESControl_Reader reader;
    EXPECT_EQ(reader.ReadFile(path.c_str()), IFSelect_RetDone) << path;
    reader.TransferRoots();
    shape = reader.OneShape();
  }
  std::vector<TopoDS_Face> faces;
  for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next())
    faces.push_back(TopoDS::Face(e.Current()));
  if (shapeOut) *shapeOut = shape;
  return faces;
}

/// A patch of the model: its evaluation and parameter rectangle.
struct Patch {
  std::function<Vec3(double, double)> position;
  double u0 = 0, u1 = 1, v0 = 0, v1 = 1;
};

/// Each read face is matched to a patch and to one of the four reflections of its parameter
/// rectangle (IGES has no face orientation: Open CASCADE's writer reverses the u parameter
/// of a reversed face's surface instead), the pair that agrees best on a 3 × 3 grid, then
/// compared on a kGrid × kGrid grid. Returns the largest distance; every patch must be
/// matched once.
double roundTripDeviation(const std::vector<TopoDS_Face>& faces,
                          const std::vector<Patch>& patches) {
  EXPECT_EQ(faces.size(), patches.size());
  std::vector<int> used(patches.size(), 0);
  double worst = 0.0;
  for (const TopoDS_Face& face : faces) {
    const Handle(Geom_Surface) surface = BRep_Tool::Surface(face);
    EXPECT_FALSE(Handle(Geom_BSplineSurface)::DownCast(surface).IsNull()) << "not a B-spline";
    double u0, u1, v0, v1;
    BRepTools::UVBounds(face, u0, u1, v0, v1);
    // The distance between the face at (s, t) ∈ [0,1]² of its bounds and patch k at the
    // point of its rectangle that `flip` (bit 0: s, bit 1: t) says.
    const auto distance = [&](std::size_t k, int flip, double s, double t) {
      const Patch& p = patches[k];
      const double ps = (flip & 1) ? 1 - s : s, pt = (flip & 2) ? 1 - t : t;
      const Vec3 q = p.position(p.u0 + (p.u1 - p.u0) * ps, p.v0 + (p.v1 - p.v0) * pt);
      return (toVec(surface->Value(u0 + (u1 - u0) * s, v0 + (v1 - v0) * t)) - q).norm();
    };
    std::size_t best = 0;
    int bestFlip = 0;
    double bestDistance = INFINITY;
    for (std::size_t k = 0; k < patches.size(); ++k)
      for (int flip = 0; flip < 4; ++flip) {
        double d = 0.0;
        for (double s : {0.1, 0.5, 0.9})
          for (double t : {0.2, 0.5, 0.7}) d = std::max(d, distance(k, flip, s, t));
        if (d < bestDistance) bestDistance = d, best = k, bestFlip = flip;
      }
    ++used[best];
    const Patch& p = patches[best];
    EXPECT_NEAR(u1 - u0, p.u1 - p.u0, 1e-9);
    EXPECT_NEAR(v1 - v0, p.v1 - p.v0, 1e-9);
    for (int i = 0; i < kGrid; ++i)
      for (int j = 0; j < kGrid; ++j)
        worst = std::max(worst, distance(best, bestFlip, i / (kGrid - 1.0), j / (kGrid - 1.0)));
  }
  for (std::size_t k = 0; k < used.size(); ++k) EXPECT_EQ(used[k], 1) << "patch " << k;
  return worst;
}

std::vector<Patch> patchesOf(const VertexFrameSurface& surface) {
  std::vector<Patch> out;
  for (const VertexFramePatch& patch : surface.patches)
    out.push_back({[&patch](double u, double v) { return patch.position(u, v); }});
  return out;
}

std::vector<Patch> patchesOf(const SolvedSpectral& solved) {
  std::vector<Patch> out;
  for (std::size_t k = 0; k < solved.patchCount(); ++k) {
    const SpectralPatch& patch = solved.patchAt(k);
    const auto [u0, u1] = solved.range(k);
    out.push_back({[&patch](double u, double v) { return patch.position(u, v); }, u0, u1, 0.0,
                   2 * std::numbers::pi});
  }
  return out;
}

using testing::solveSpectralFile;

class RoundTrip : public ::testing::TestWithParam<CadFormat> {
 protected:
  std::string file(const std::string& stem) const {
    return dir_.file(stem + (GetParam() == CadFormat::Step ? ".step" : ".igs"));
  }
  testing::TempDir dir_;
};

TEST_P(RoundTrip, ForceFreeVertexFramesAreExact) {
  const VertexFrameSurface surface = solve(loadModel(example("mug.json")).get<VertexFrameModel>());
  const NurbsModel model = toNurbs(surface);
  const std::string path = file("mug");
  const CadExportReport report = writeCad(model, path, GetParam());
  EXPECT_EQ(report.faces, surface.patches.size());
  const double deviation = roundTripDeviation(readFaces(path, GetParam()), patchesOf(surface));
  EXPECT_LE(deviation, kExactNurbsTolerance * model.diagonal);
}

TEST_P(RoundTrip, ForcesAreWithinTheTolerance) {
  for (const char* name : {"sculpt.json", "grid-forces.json"}) {
    const VertexFrameSurface surface = solve(loadModel(example(name)).get<VertexFrameModel>());
    NurbsExportOptions options;
    options.tolerance = 1e-5 * surfaceBounds(surface).diagonal();
    const NurbsModel model = toNurbs(surface, options);
    const std::string path = file("forces");
    writeCad(model, path, GetParam());
    EXPECT_LE(roundTripDeviation(readFaces(path, GetParam()), patchesOf(surface)),
              options.tolerance)
        << name;
  }
}

TEST_P(RoundTrip, SpectralPatchesAreWithinTheTolerance) {
  for (const char* name : {"shell.json", "vase-sections.json"}) {
    const SolvedSpectral solved = solveSpectralFile(example(name));
    const NurbsModel model = toNurbs(solved);
    const std::string path = file("spectral");
    writeCad(model, path, GetParam());
    EXPECT_LE(roundTripDeviation(readFaces(path, GetParam()), patchesOf(solved)), model.tolerance)
        << name;
  }
}

TEST_P(RoundTrip, BSplinePdeSurfacesAreExact) {
  std::vector<BSplineSurface> surfaces;
  std::vector<Patch> patches;
  for (KnotType type : {KnotType::Uniform, KnotType::Clamped}) {
    ControlNet net(6, 5);
    for (std::uint32_t i = 0; i <= 6; ++i)
      for (std::uint32_t j = 0; j <= 5; ++j)
        net(i, j) = Vec3(i, j + (type == KnotType::Clamped ? 8.0 : 0.0),
                         std::sin(0.9 * i) * std::cos(0.6 * j) + 0.1 * i * j);
    surfaces.push_back(solve(net, {type, type}));
  }
  for (const BSplineSurface& s : surfaces)
    patches.push_back({[&s](double u, double v) { return s.position(u, v); }});
  const NurbsModel model = toNurbs(surfaces);
  EXPECT_EQ(model.exactCount(), 2u);
  const std::string path = file("bspline");
  writeCad(model, path, GetParam());
  EXPECT_LE(roundTripDeviation(readFaces(path, GetParam()), patches),
            kExactNurbsTolerance * model.diagonal);
}

INSTANTIATE_TEST_SUITE_P(Formats, RoundTrip, ::testing::Values(CadFormat::Step, CadFormat::Iges),
                         [](const auto& info) {
                           return info.param == CadFormat::Step ? "Step" : "Iges";
                         });

TEST(OcctSurface, EqualsTheNurbsSurfaceAndItsDerivatives) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> c(-1, 1), unit(0, 1);
  VertexFramePatch patch;
  for (Vec3& k : patch.c) k = {c(rng), c(rng), c(rng)};
  const Handle(Geom_BSplineSurface) occt = toOcct(bezierPatch(patch));
  for (int k = 0; k < 200; ++k) {
    const double u = unit(rng), v = unit(rng);
    gp_Pnt p;
    gp_Vec du, dv;
    occt->D1(u, v, p, du, dv);
    const SurfacePoint want = patch.evaluate(u, v);
    EXPECT_LE((toVec(p) - want.p).norm(), 1e-12);
    EXPECT_LE((Vec3(du.X(), du.Y(), du.Z()) - want.du).norm(), 1e-12);
    EXPECT_LE((Vec3(dv.X(), dv.Y(), dv.Z()) - want.dv).norm(), 1e-12);
  }
}

/// Free edges of a shape read back from a file: its edges bounding only one face.
std::size_t freeEdgesOf(const TopoDS_Shape& shape) {
  TopTools_IndexedDataMapOfShapeListOfShape edgeFaces;
  TopExp::MapShapesAndAncestors(shape, TopAbs_EDGE, TopAbs_FACE, edgeFaces);
  std::size_t free = 0;
  for (int e = 1; e <= edgeFaces.Extent(); ++e)
    if (!BRep_Tool::Degenerated(TopoDS::Edge(edgeFaces.FindKey(e))) &&
        edgeFaces.FindFromIndex(e).Extent() == 1)
      ++free;
  return free;
}

TEST(Sewing, AClosedTorusHasNoFreeEdgesAndAnOpenSheetItsBorder) {
  std::mt19937 rng(8);
  testing::TempDir dir;
  for (bool closed : {true, false}) {
    testing::LatticeOptions o;
    o.closedU = o.closedV = closed;
    o.randomOrientation = true;
    o.rows = 3;
    o.cols = 4;
    const VertexFrameSurface surface = solve(testing::latticeModel(o, rng));
    const std::string path = dir.file("lattice.step");
    const CadExportReport report = writeCad(toNurbs(surface), path, CadFormat::Step);
    EXPECT_EQ(report.faces, 12u);
    EXPECT_EQ(report.shells, 1u);
    EXPECT_EQ(report.multipleEdges, 0u);
    // The open 4 × 3 sheet's border: 2 (4 + 3) frame sides.
    EXPECT_EQ(report.freeEdges, closed ? 0u : 14u) << (closed ? "torus" : "sheet");
    TopoDS_Shape shape;
    EXPECT_EQ(readFaces(path, CadFormat::Step, &shape).size(), 12u);
    EXPECT_EQ(freeEdgesOf(shape), closed ? 0u : 14u) << "read back";
  }
}

TEST(Sewing, EveryVertexFrameExampleKeepsExactlyItsUnsharedEdgesFree) {
  testing::TempDir dir;
  for (const auto& entry : std::filesystem::directory_iterator(example(""))) {
    if (entry.path().extension() != ".json") continue;
    const AnyModel any = loadModel(entry.path().string());
    const auto* model = any.as<VertexFrameModel>();
    if (!model) continue;
    const VertexFrameSurface surface = solve(*model);
    std::size_t unshared = 0;
    for (const ModelEdge& edge : surface.topology->edges)
      unshared += edge.sideCount == 1 && !edge.collapsed();
    const CadExportReport report =
        writeCad(toNurbs(surface), dir.file("model.step"), CadFormat::Step);
    EXPECT_EQ(report.freeEdges, unshared) << entry.path();
    EXPECT_EQ(report.multipleEdges, 0u) << entry.path();
  }
}

TEST(CadFormatFromPath, KnowsStepAndIgesExtensionsInAnyCase) {
  EXPECT_EQ(cadFormatFromPath("a.step"), CadFormat::Step);
  EXPECT_EQ(cadFormatFromPath("dir/a.STP"), CadFormat::Step);
  EXPECT_EQ(cadFormatFromPath("a.igs"), CadFormat::Iges);
  EXPECT_EQ(cadFormatFromPath("a.Iges"), CadFormat::Iges);
  EXPECT_THROW(cadFormatFromPath("a.obj"), CadError);
  EXPECT_THROW(cadFormatFromPath("step"), CadError);
}

TEST(WriteCad, AnUnwritablePathThrowsAndLeavesNothing) {
  const VertexFrameSurface surface = solve(loadModel(example("mug.json")).get<VertexFrameModel>());
  testing::TempDir dir;
  EXPECT_THROW(writeCad(toNurbs(surface), dir.file("missing/x.step"), CadFormat::Step), CadError);
  EXPECT_TRUE(dir.entries().empty());
}

}  // namespace
}  // namespace pdesurf
