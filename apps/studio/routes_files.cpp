// The studio's routes of files (routes.hpp): listing the root's models, open, save, save as,
// a new model, export to a mesh or CAD file, and the autosave's recovery. Every path a
// request names resolves inside the root folder (root_sandbox.hpp).
#include <algorithm>
#include <filesystem>
#include <optional>
#include <system_error>
#include <vector>

#include <fmt/format.h>

#include "pdesurf/atomic_file.hpp"
#include "pdesurf/cad_export.hpp"
#include "pdesurf/edit_io.hpp"
#include "pdesurf/mesh_io.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/nurbs.hpp"
#include "routes.hpp"

namespace pdesurf::studio {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

/// A model file a request names (save as, new): inside the root, ending in .json.
fs::path modelFilePath(const RootSandbox& sandbox, const std::string& requested) {
  const fs::path path = sandbox.resolve(requested);
  if (path.extension() != ".json")
    fail(400, fmt::format("{}: a model file ends in .json", requested));
  return path;
}

/// The CAD format a path names (.step .stp .iges .igs), if any.
std::optional<CadFormat> cadFormatOf(const fs::path& path) {
  try {
    return cadFormatFromPath(path.string());
  } catch (const CadError&) {
    return std::nullopt;
  }
}

/// Writes the open model as B-spline faces to a STEP or IGES file, as `pdesurf export` does
/// with its default tolerance (a face that misses it is written as its finest fit; the answer
/// counts such faces); what it wrote, for the page.
Json exportCad(const Studio& studio, const fs::path& path, CadFormat format) {
  NurbsExportOptions options;
  options.keepBest = true;
  const NurbsModel nurbs = toNurbs(studio.document.session().solved(), options);
  CadExportReport report;
  try {
    report = writeCad(nurbs, path.string(), format);
  } catch (const CadError& e) {
    fail(500, e.what());
  }
  return {
      {"path", studio.sandbox.relative(path)}, {"faces", nurbs.faces.size()},
      {"exactFaces", nurbs.exactCount()},      {"facesOverTolerance", nurbs.overToleranceCount()},
      {"maxDeviation", nurbs.maxDeviation()},  {"shells", report.shells}};
}

/// An export request's "resolution" (400 when it is out of range).
std::uint32_t exportResolution(const Json& body) {
  auto it = body.find("resolution");
  if (it == body.end()) return kDefaultExportResolution;
  if (!it->is_number_unsigned() || it->get<std::uint64_t>() < kMinResolution ||
      it->get<std::uint64_t>() > kMaxExportResolution)
    fail(400, fmt::format("$.resolution: expected a whole number from {} to {}", kMinResolution,
                          kMaxExportResolution));
  return it->get<std::uint32_t>();
}

/// Writes the open model's surface mesh (the page's tessellation cache is left alone); what
/// it wrote, for the page.
Json exportMesh(const Studio& studio, std::uint32_t resolution, const fs::path& path) {
  const Mesh mesh = tessellate(studio.document.session().solved(), {resolution});
  try {
    writeMesh(mesh, path.string());
  } catch (const MeshIoError& e) {
    fail(500, e.what());
  }
  return {{"path", studio.sandbox.relative(path)},
          {"vertices", mesh.vertexCount()},
          {"triangles", mesh.triangleCount()}};
}

}  // namespace

void addFileRoutes(const Studio& studio) {
  Document& doc = studio.document;
  const RootSandbox& sandbox = studio.sandbox;

  studio.server.Get("/api/files",
                    studio.guarded([&sandbox](const httplib::Request&, httplib::Response& res) {
                      std::vector<std::string> files;
                      std::error_code ec;
                      fs::recursive_directory_iterator it(
                          sandbox.root(), fs::directory_options::skip_permission_denied, ec);
                      for (; !ec && it != fs::recursive_directory_iterator(); it.increment(ec))
                        if (it->path().extension() == ".json" && it->is_regular_file(ec))
                          files.push_back(sandbox.relative(it->path()));
                      std::sort(files.begin(), files.end());
                      sendJson(res, {{"files", files}});
                    }));

  studio.server.Post("/api/open", studio.guarded([&doc, &sandbox](const httplib::Request& req,
                                                                  httplib::Response& res) {
    const std::string requested = stringMember(bodyObject(req), "path");
    const fs::path path = sandbox.resolve(requested);
    std::error_code ec;
    if (!fs::exists(path, ec)) fail(404, fmt::format("{}: no such file", requested));
    if (!fs::is_regular_file(path, ec)) fail(400, fmt::format("{}: not a file", requested));
    doc.open(path, sandbox.relative(path));
    sendJson(res, doc.openedStatus());
  }));

  const auto savedStatus = [&doc, &sandbox] {
    Json out = doc.status();
    out["path"] = sandbox.relative(doc.path());
    return out;
  };

  studio.server.Post("/api/save", studio.guarded([&doc, savedStatus](const httplib::Request&,
                                                                     httplib::Response& res) {
    doc.save(doc.path());
    sendJson(res, savedStatus());
  }));

  studio.server.Post("/api/save-as",
                     studio.guarded([&doc, &sandbox, savedStatus](const httplib::Request& req,
                                                                  httplib::Response& res) {
                       const std::string requested = stringMember(bodyObject(req), "path");
                       const fs::path path = modelFilePath(sandbox, requested);
                       std::error_code ec;
                       if (fs::is_directory(path, ec))
                         fail(400, fmt::format("{}: is a folder", requested));
                       sandbox.makeParent(path);
                       doc.save(path);
                       sendJson(res, savedStatus());
                     }));

  // A new vertex-frame model (newFrameModel) written to a new file and opened.
  studio.server.Post("/api/new", studio.guarded([&doc, &sandbox](const httplib::Request& req,
                                                                 httplib::Response& res) {
    const std::string requested = stringMember(bodyObject(req), "path");
    const NewModelOptions options = parseNewModel(req.body);
    const fs::path path = modelFilePath(sandbox, requested);
    std::error_code ec;
    if (fs::exists(path, ec))
      fail(409, fmt::format("{}: exists already (choose another name)", requested));
    sandbox.makeParent(path);
    try {
      writeFileAtomically(path.string(), serializeModel(AnyModel(newFrameModel(options))));
    } catch (const std::exception& e) {
      fail(500, e.what());
    }
    doc.open(path, sandbox.relative(path));
    sendJson(res, doc.openedStatus());
  }));

  studio.server.Post("/api/export", studio.guarded([&studio, &sandbox](const httplib::Request& req,
                                                                       httplib::Response& res) {
    const Json body = bodyObject(req);
    const std::string requested = stringMember(body, "path");
    const fs::path path = sandbox.resolve(requested);
    const std::optional<CadFormat> cad = cadFormatOf(path);
    try {
      if (!cad) meshFormatFromPath(path.string());
    } catch (const MeshIoError&) {
      fail(400, fmt::format("{}: unknown format (known: .obj .ply .stl .glb .off .step .stp "
                            ".iges .igs)",
                            requested));
    }
    const std::uint32_t resolution = exportResolution(body);
    std::error_code ec;
    if (fs::is_directory(path, ec)) fail(400, fmt::format("{}: is a folder", requested));
    sandbox.makeParent(path);
    sendJson(res, cad ? exportCad(studio, path, *cad) : exportMesh(studio, resolution, path));
  }));

  studio.server.Post("/api/recover",
                     studio.guarded([&doc](const httplib::Request&, httplib::Response& res) {
                       doc.recover();
                       sendJson(res, doc.status());
                     }));

  studio.server.Post("/api/discard-recovery",
                     studio.guarded([&doc](const httplib::Request&, httplib::Response& res) {
                       doc.discardRecovery();
                       sendJson(res, doc.status());
                     }));
}

}  // namespace pdesurf::studio
