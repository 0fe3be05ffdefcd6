// STEP and IGES files of pdesurf models through Open CASCADE: every face a B-spline surface
// (include/pdesurf/nurbs.hpp), the faces sewn into shells (docs/nurbs-export.md). The
// pdesurf::occt library; this header names no Open CASCADE type.
#pragma once

#include <cstddef>
#include <string>

#include "pdesurf/error.hpp"
#include "pdesurf/nurbs.hpp"

namespace pdesurf {

enum class CadFormat { Step, Iges };

/// The format an output path's extension names: .step or .stp, .igs or .iges (any case).
/// Throws CadError naming the extensions it knows.
CadFormat cadFormatFromPath(const std::string& path);

struct CadExportOptions {
  /// Distance below which sewing joins two edges; ≤ 0: the model's tolerance
  /// (NurbsModel::tolerance).
  double sewingTolerance = 0.0;
};

/// What sewing made of the faces.
struct CadExportReport {
  std::size_t faces = 0;
  std::size_t shells = 0;            ///< connected sheets after sewing (a lone face: one)
  std::size_t freeEdges = 0;         ///< edges on one face only (the open boundary)
  std::size_t multipleEdges = 0;     ///< edges shared by more than two faces
  std::size_t degeneratedEdges = 0;  ///< edges collapsed to a point (poles, shell tips)
  double sewingTolerance = 0.0;
};

/// Builds one face per NurbsFace (Geom_BSplineSurface on its whole domain), sews them with
/// BRepBuilderAPI_Sewing and writes STEP (AP214, millimetres, reals to 17 significant
/// digits) or IGES (5.3, trimmed B-spline surfaces, millimetres). The file appears whole or
/// not at all (writeFileAtomically). Throws CadError on failure.
CadExportReport writeCad(const NurbsModel& model, const std::string& path, CadFormat format,
                         const CadExportOptions& options = {});

}  // namespace pdesurf
