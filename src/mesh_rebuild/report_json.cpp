// The rebuild's report as `pdesurf rebuild --as cross-sections --json` prints it
// (include/pdesurf/mesh_rebuild.hpp).
#include <string>

#include <nlohmann/json.hpp>

#include "pdesurf/mesh_rebuild.hpp"

namespace pdesurf {

namespace {

using Json = nlohmann::ordered_json;

Json oneWay(const OneWayDistance& d) {
  return {{"rms", d.rms},   {"rms_relative", d.rmsRelative},
          {"mean", d.mean}, {"mean_relative", d.meanRelative},
          {"max", d.max},   {"max_relative", d.maxRelative}};
}

}  // namespace

std::string rebuildReportJson(const RebuildReport& report, const RebuildOptions& options,
                              const std::string& output) {
  const MeshDistance& d = report.distance;
  const NormalDeviation& n = report.normals;
  Json j = {
      {"mesh", options.source},
      {"as", rebuildKindName(report.kind)},
      {"output", output},
      {"axis", axisName(options.slice.axis)},
      {"sections", report.sections},
      {"from", report.from},
      {"to", report.to},
      {"modes", options.modes},
      {"exact", options.exact},
      {"a", options.a},
      {"ends", chainEndsName(options.ends)},
      {"diagonal", d.diagonal},
      {"model_to_part", oneWay(d.aToB)},
      {"part_to_model", oneWay(d.bToA)},
      {"normals",
       {{"folded_area", n.foldedArea}, {"rms_degrees", n.rmsDegrees}, {"reversed", n.reversed}}},
      {"model_storage_bytes", report.storageBytes},
      {"part_storage_bytes", report.referenceStorageBytes},
      {"part_triangles", report.referenceTriangles},
      {"part_vertices", report.referenceVertices},
      {"ms",
       {{"read", report.ms.read}, {"rebuild", report.ms.fit}, {"measure", report.ms.measure}}}};
  if (report.loft) {
    if (report.loft->distance)
      j["loft"] = {{"model_to_part", oneWay(report.loft->distance->aToB)},
                   {"part_to_model", oneWay(report.loft->distance->bToA)}};
    else
      j["loft"] = {{"failed", report.loft->failure}};
  }
  return j.dump(2);
}

}  // namespace pdesurf
