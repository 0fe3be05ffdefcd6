// STEP and IGES export through Open CASCADE: NurbsSurface -> Geom_BSplineSurface -> faces,
// sewn, written to a temporary file and renamed (docs/nurbs-export.md).
#include "pdesurf/cad_export.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <sstream>

#include <fmt/format.h>

#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRep_Tool.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <IGESData_IGESWriter.hxx>
#include <IGESSelect_WorkLibrary.hxx>
#include <Interface_FloatWriter.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Writer.hxx>
#include <Standard_Failure.hxx>
#include <StepAP214.hxx>
#include <StepAP214_Protocol.hxx>
#include <StepData_StepModel.hxx>
#include <StepData_StepWriter.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>

#include "pdesurf/atomic_file.hpp"
#include "pdesurf/occt_convert.hpp"

namespace pdesurf {

namespace {

/// Distinct knots and their multiplicities, as Open CASCADE takes them.
void splitKnots(const std::vector<double>& full, TColStd_Array1OfReal& knots,
                TColStd_Array1OfInteger& mults) {
  std::vector<double> distinct;
  std::vector<int> counts;
  for (double t : full) {
    if (!distinct.empty() && t == distinct.back()) {
      ++counts.back();
    } else {
      distinct.push_back(t);
      counts.push_back(1);
    }
  }
  knots.Resize(1, static_cast<int>(distinct.size()), false);
  mults.Resize(1, static_cast<int>(distinct.size()), false);
  for (std::size_t k = 0; k < distinct.size(); ++k) {
    knots.SetValue(static_cast<int>(k) + 1, distinct[k]);
    mults.SetValue(static_cast<int>(k) + 1, counts[k]);
  }
}

/// Open CASCADE's messages go to its default printer (stdout): keep them off, the CLI
/// reports for itself.
void silenceOcct() {
  static const bool done = [] {
    Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_Printer));
    return true;
  }();
  (void)done;
}

/// Reals with 16 significant digits ("-2.341740000000000E-01": at most 23 characters,
/// which Open CASCADE's 24-character buffers hold); its writers default to 12 (STEP) and
/// 10 (IGES). Zero suppression stays off: Open CASCADE's looks for the exponent in the
/// first 16 characters only and would drop it.
void fullPrecision(Interface_FloatWriter& writer) {
  writer.SetFormat("%.15E");
  writer.SetZeroSuppress(false);
}

/// The text of an interface model written by `Writer` (StepData_StepWriter or
/// IGESData_IGESWriter) with `protocol`, its reals at full precision.
template <class Writer, class Model, class Protocol>
std::string modelText(const Model& model, const Protocol& protocol, const std::string& path,
                      const char* format) {
  Writer out(model);
  fullPrecision(out.FloatWriter());
  out.SendModel(protocol);
  std::ostringstream text;
  if (!out.Print(text))
    throw CadError(path, fmt::format("Open CASCADE could not write the {} data", format));
  return text.str();
}

std::string stepText(const TopoDS_Shape& shape, const std::string& path) {
  STEPControl_Controller::Init();
  Interface_Static::SetCVal("write.step.schema", "AP214IS");
  Interface_Static::SetCVal("write.step.unit", "MM");
  STEPControl_Writer writer;
  if (writer.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone)
    throw CadError(path, "Open CASCADE could not translate the shape to STEP");
  return modelText<StepData_StepWriter>(writer.Model(), StepAP214::Protocol(), path, "STEP");
}

std::string igesText(const TopoDS_Shape& shape, const std::string& path) {
  IGESControl_Controller::Init();
  IGESControl_Writer writer("MM", 0);  // mode 0: faces as trimmed surfaces (entity 144)
  if (!writer.AddShape(shape))
    throw CadError(path, "Open CASCADE could not translate the shape to IGES");
  writer.ComputeModel();
  // What IGESControl_Writer::Write does, with the reals at full precision.
  return modelText<IGESData_IGESWriter>(writer.Model(), IGESSelect_WorkLibrary::DefineProtocol(),
                                        path, "IGES");
}

}  // namespace

Handle(Geom_BSplineSurface) toOcct(const NurbsSurface& s) {
  TColgp_Array2OfPnt poles(1, static_cast<int>(s.uCount), 1, static_cast<int>(s.vCount));
  for (std::uint32_t i = 0; i < s.uCount; ++i)
    for (std::uint32_t j = 0; j < s.vCount; ++j) {
      const Vec3& p = s.pole(i, j);
      poles.SetValue(static_cast<int>(i) + 1, static_cast<int>(j) + 1, gp_Pnt(p.x(), p.y(), p.z()));
    }
  TColStd_Array1OfReal uKnots(1, 1), vKnots(1, 1);
  TColStd_Array1OfInteger uMults(1, 1), vMults(1, 1);
  splitKnots(s.uKnots, uKnots, uMults);
  splitKnots(s.vKnots, vKnots, vMults);
  return new Geom_BSplineSurface(poles, uKnots, vKnots, uMults, vMults, static_cast<int>(s.uDegree),
                                 static_cast<int>(s.vDegree));
}

TopoDS_Face makeFace(const NurbsSurface& surface, double tolerance) {
  BRepBuilderAPI_MakeFace make(toOcct(surface), surface.uMin(), surface.uMax(), surface.vMin(),
                               surface.vMax(), tolerance);
  if (!make.IsDone()) throw CadError("Open CASCADE could not make a face of a surface");
  return make.Face();
}

CadFormat cadFormatFromPath(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".step" || ext == ".stp") return CadFormat::Step;
  if (ext == ".igs" || ext == ".iges") return CadFormat::Iges;
  throw CadError(
      path, fmt::format("unknown extension '{}' (export writes .step, .stp, .igs, .iges)", ext));
}

CadExportReport writeCad(const NurbsModel& model, const std::string& path, CadFormat format,
                         const CadExportOptions& options) {
  silenceOcct();
  CadExportReport report;
  report.faces = model.faces.size();
  report.sewingTolerance =
      options.sewingTolerance > 0.0 ? options.sewingTolerance : model.tolerance;
  try {
    BRepBuilderAPI_Sewing sewing(report.sewingTolerance);
    for (const NurbsFace& face : model.faces)
      sewing.Add(makeFace(face.surface, report.sewingTolerance));
    sewing.Perform();
    const TopoDS_Shape shape = sewing.SewedShape();
    report.freeEdges = static_cast<std::size_t>(sewing.NbFreeEdges());
    report.multipleEdges = static_cast<std::size_t>(sewing.NbMultipleEdges());
    TopTools_IndexedMapOfShape shells, edges;
    TopExp::MapShapes(shape, TopAbs_SHELL, shells);
    TopExp::MapShapes(shape, TopAbs_EDGE, edges);
    report.shells = static_cast<std::size_t>(shells.Extent());
    for (TopExp_Explorer lone(shape, TopAbs_FACE, TopAbs_SHELL); lone.More(); lone.Next())
      ++report.shells;  // a face sewn to nothing is a sheet of its own
    for (int e = 1; e <= edges.Extent(); ++e)
      if (BRep_Tool::Degenerated(TopoDS::Edge(edges(e)))) ++report.degeneratedEdges;
    const std::string text =
        format == CadFormat::Step ? stepText(shape, path) : igesText(shape, path);
    writeFileAtomically(path, text);
  } catch (const Standard_Failure& e) {
    throw CadError(path, fmt::format("Open CASCADE failed: {}", e.GetMessageString()));
  } catch (const FileError& e) {  // the write itself
    throw CadError(e.file(), e.message());
  }
  return report;
}

}  // namespace pdesurf
