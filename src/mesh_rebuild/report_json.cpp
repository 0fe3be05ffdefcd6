// The rebuild's report as `pdesurf rebuild --as cross-sections --json` prints it, and the
// JSON of the distances and normals it holds, which `pdesurf compare --json` writes too
// (include/pdesurf/mesh_rebuild.hpp).
#include <string>

#include <nlohmann/json.hpp>

#include "pdesurf/mesh_rebuild.hpp"

namespace pdesurf {

using Json = nlohmann::ordered_json;

Json oneWayDistanceJson(const OneWayDistance& d, DistanceFields fields) {
  const bool all = fields == DistanceFields::All;
  Json j = Json::object();
  if (all) j["samples"] = d.samples;
  j["rms"] = d.rms;
  j["rms_relative"] = d.rmsRelative;
  j["mean"] = d.mean;
  j["mean_relative"] = d.meanRelative;
  j["max"] = d.max;
  j["max_relative"] = d.maxRelative;
  if (all) {
    j["max_at"] = {d.maxAt.x(), d.maxAt.y(), d.maxAt.z()};
    j["cover_radius"] = d.coverRadius;
  }
  return j;
}

Json normalDeviationJson(const NormalDeviation& n) {
  return {{"folded_area", n.foldedArea}, {"rms_degrees", n.rmsDegrees}, {"reversed", n.reversed}};
}

std::string rebuildReportJson(const RebuildReport& report, const RebuildOptions& options,
                              const std::string& output) {
  const MeshDistance& d = report.distance;
  const auto figures = [](const OneWayDistance& w) {
    return oneWayDistanceJson(w, DistanceFields::Figures);
  };
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
      {"model_to_part", figures(d.aToB)},
      {"part_to_model", figures(d.bToA)},
      {"normals", normalDeviationJson(report.normals)},
      {"model_storage_bytes", report.storageBytes},
      {"part_storage_bytes", report.referenceStorageBytes},
      {"part_triangles", report.referenceTriangles},
      {"part_vertices", report.referenceVertices},
      {"ms",
       {{"read", report.ms.read}, {"rebuild", report.ms.fit}, {"measure", report.ms.measure}}}};
  if (report.loft) {
    if (report.loft->distance)
      j["loft"] = {{"model_to_part", figures(report.loft->distance->aToB)},
                   {"part_to_model", figures(report.loft->distance->bToA)}};
    else
      j["loft"] = {{"failed", report.loft->failure}};
  }
  return j.dump(2);
}

}  // namespace pdesurf
