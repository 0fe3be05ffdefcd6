// Open CASCADE's loft through closed sections (include/pdesurf/occt_loft.hpp).
#include "pdesurf/occt_loft.hpp"

#include <string>

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepOffsetAPI_ThruSections.hxx>
#include <BRep_Tool.hxx>
#include <GeomAPI_Interpolate.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Poly_Triangulation.hxx>
#include <Standard_Failure.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Wire.hxx>

namespace pdesurf {

namespace {

/// Interpolation tolerance: points closer than this count as one (OCCT's confusion).
constexpr double kInterpolationTolerance = 1e-9;

TopoDS_Wire sectionWire(const SampledCurve& section, std::size_t index) {
  const int n = static_cast<int>(section.points.size());
  Handle(TColgp_HArray1OfPnt) points = new TColgp_HArray1OfPnt(1, n);
  for (int j = 0; j < n; ++j) {
    const Vec3& p = section.points[static_cast<std::size_t>(j)];
    points->SetValue(j + 1, gp_Pnt(p.x(), p.y(), p.z()));
  }
  GeomAPI_Interpolate interpolate(points, /*periodic=*/true, kInterpolationTolerance);
  interpolate.Perform();
  if (!interpolate.IsDone())
    throw LoftError("section " + std::to_string(index) + ": no periodic B-spline interpolates it");
  BRepBuilderAPI_MakeEdge edge(interpolate.Curve());
  BRepBuilderAPI_MakeWire wire(edge.Edge());
  return wire.Wire();
}

}  // namespace

Mesh occtLoft(std::span<const SampledCurve> sections, double deflection) {
  Mesh mesh;
  try {
    BRepOffsetAPI_ThruSections loft(/*isSolid=*/false, /*ruled=*/false);
    for (std::size_t i = 0; i < sections.size(); ++i) loft.AddWire(sectionWire(sections[i], i));
    loft.CheckCompatibility(false);  // the sections are aligned already
    loft.Build();
    if (!loft.IsDone()) throw LoftError("BRepOffsetAPI_ThruSections did not build a surface");
    const TopoDS_Shape shape = loft.Shape();
    BRepMesh_IncrementalMesh mesher(shape, deflection, /*isRelative=*/false, 0.2);
    for (TopExp_Explorer it(shape, TopAbs_FACE); it.More(); it.Next()) {
      const TopoDS_Face face = TopoDS::Face(it.Current());
      TopLoc_Location where;
      const Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(face, where);
      if (tri.IsNull()) continue;
      const auto base = static_cast<std::uint32_t>(mesh.vertexCount());
      const gp_Trsf move = where.Transformation();
      for (int k = 1; k <= tri->NbNodes(); ++k) {
        const gp_Pnt p = tri->Node(k).Transformed(move);
        mesh.positions.insert(
            mesh.positions.end(),
            {static_cast<float>(p.X()), static_cast<float>(p.Y()), static_cast<float>(p.Z())});
      }
      const bool reversed = face.Orientation() == TopAbs_REVERSED;
      for (int t = 1; t <= tri->NbTriangles(); ++t) {
        int a = 0, b = 0, c = 0;
        tri->Triangle(t).Get(a, b, c);
        if (reversed) std::swap(b, c);
        mesh.indices.insert(mesh.indices.end(), {base + static_cast<std::uint32_t>(a - 1),
                                                 base + static_cast<std::uint32_t>(b - 1),
                                                 base + static_cast<std::uint32_t>(c - 1)});
      }
    }
  } catch (const Standard_Failure& e) {
    throw LoftError(std::string("Open CASCADE: ") + e.GetMessageString());
  }
  if (mesh.triangleCount() == 0) throw LoftError("the loft has no faces to mesh");
  return mesh;
}

}  // namespace pdesurf
