// The studio's routes of the surface (routes.hpp): GET /api/mesh, the frame overlay's true
// boundary curves, the patch of every triangle, points and parameters of a patch, and the
// analytic curvature at the mesh's vertices.
#include <vector>

#include "pdesurf/analysis.hpp"
#include "pdesurf/edit_io.hpp"
#include "routes.hpp"

namespace pdesurf::studio {
namespace {

using Json = nlohmann::json;

/// The bytes of `count` values at `data`, as they lie in memory.
template <class T>
std::string bytesOf(const T* data, std::size_t count) {
  return {reinterpret_cast<const char*>(data), sizeof(T) * count};
}

/// The four sides of each patch of `surface` (its parameter square's edges, in the order
/// v = 0, u = 1, v = 1, u = 0), `samples` points each, as little-endian float32.
std::string boundaryCurves(const VertexFrameSurface& surface, std::uint32_t samples) {
  std::vector<float> out;
  out.reserve(std::size_t{12} * samples * surface.patches.size());
  for (const VertexFramePatch& patch : surface.patches)
    for (int side = 0; side < 4; ++side)
      for (std::uint32_t i = 0; i < samples; ++i) {
        const double t = static_cast<double>(i) / (samples - 1);
        const double u = side == 0 ? t : side == 1 ? 1.0 : side == 2 ? 1.0 - t : 0.0;
        const double v = side == 0 ? 0.0 : side == 1 ? t : side == 2 ? 1.0 : 1.0 - t;
        const Vec3 p = patch.position(u, v);
        for (int c = 0; c < 3; ++c) out.push_back(static_cast<float>(p[c]));
      }
  return bytesOf(out.data(), out.size());
}

/// The mesh GET /api/mesh gives for `request`: the one last sent when it is of the open
/// model's revision, else the model tessellated again into `fresh`.
const Mesh& requestedMesh(const Studio& studio, const MeshRequest& request, Mesh& fresh) {
  const Document& doc = studio.document;
  if (const Mesh* sent = studio.meshes.sent(request.resolution, doc.revision(), request.options))
    return *sent;
  fresh = tessellate(studio.document.session().solved(request.options), {request.resolution});
  return fresh;
}

}  // namespace

void addSurfaceRoutes(const Studio& studio) {
  Document& doc = studio.document;

  studio.server.Get("/api/mesh", studio.guarded([&studio, &doc](const httplib::Request& req,
                                                                httplib::Response& res) {
    sendMesh(studio, meshRequest(req, doc), res);
  }));

  // The true boundary curves of every patch (the surface view's frame overlay): float32
  // [patch][side v=0, u=1, v=1, u=0][sample][xyz], `samples` points per side.
  studio.server.Get("/api/boundaries",
                    studio.guarded([&doc](const httplib::Request& req, httplib::Response& res) {
                      doc.requireEditable();
                      std::uint32_t samples = kDefaultMeshResolution + 1;
                      if (req.has_param("samples"))
                        samples = parseUint(req.get_param_value("samples"), kMinResolution,
                                            kMaxMeshResolution, "samples");
                      const SolvedModel& solved = doc.session().solved(solveOptions(req, doc));
                      sendBinary(res, boundaryCurves(*solved.frames(), samples), doc.revision());
                    }));

  // The patch (frame) of every triangle of the mesh at `resolution` (uint32 each, as
  // GET /api/mesh lays it out for this revision): the page picks frames on the surface.
  studio.server.Get("/api/patch-ids", studio.guarded([&studio, &doc](const httplib::Request& req,
                                                                     httplib::Response& res) {
    doc.requireEditable();
    Mesh fresh;
    const Mesh& mesh = requestedMesh(studio, meshRequest(req, doc), fresh);
    sendBinary(res, bytesOf(mesh.patchIds.data(), mesh.patchIds.size()), doc.revision());
  }));

  // Points of one patch and their parameters (edit_io.hpp: PatchQuery), solved as the
  // query's solver says: the page places force regions on the surface with them.
  const auto patchRoute = [&studio, &doc](bool withPoints) {
    return studio.guarded([&doc, withPoints](const httplib::Request& req, httplib::Response& res) {
      doc.requireEditable();
      const VertexFrameSurface& surface = *doc.session().solved(solveOptions(req, doc)).frames();
      const PatchQuery q = parsePatchQuery(req.body, surface.patches.size(), withPoints);
      const VertexFramePatch& patch = surface.patches[q.frame];
      Json out = Json::array();
      for (const Vec3& p : q.points) {
        const auto [u, v] = nearestParameters(patch, p);
        out.push_back({u, v});
      }
      for (const auto& [u, v] : q.uv) {
        const Vec3 p = patch.evaluate(u, v).p;
        out.push_back({p.x(), p.y(), p.z()});
      }
      sendJson(res, {{withPoints ? "uv" : "points", out}});
    });
  };
  studio.server.Post("/api/patch-uv", patchRoute(true));
  studio.server.Post("/api/patch-points", patchRoute(false));

  // The analytic mean and Gaussian curvature at every vertex of the mesh GET /api/mesh
  // gives for the same parameters: float32 [vertex][H, K] (analysis.hpp: meshCurvatures).
  studio.server.Get("/api/curvature", studio.guarded([&studio, &doc](const httplib::Request& req,
                                                                     httplib::Response& res) {
    doc.requireEditable();
    const MeshRequest request = meshRequest(req, doc);
    const VertexFrameSurface& surface = *doc.session().solved(request.options).frames();
    Mesh fresh;
    const Mesh& mesh = requestedMesh(studio, request, fresh);
    const std::vector<float> values = meshCurvatures(surface, mesh, request.resolution);
    sendBinary(res, bytesOf(values.data(), values.size()), doc.revision());
  }));
}

}  // namespace pdesurf::studio
