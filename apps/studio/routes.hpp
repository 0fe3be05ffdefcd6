// The studio's HTTP routes (apps/studio/README.md lists them), grouped by concern:
// routes_model.cpp (the model and its edits, undo, redo), routes_surface.cpp (meshes and
// what the page draws and picks on the surface), routes_files.cpp (opening, saving, new
// models, export, the autosave's recovery). routes_common.cpp holds what they share: the
// guard every handler runs in, and the parsing of request parameters.
#pragma once

#include <cstdint>
#include <functional>
#include <mutex>
#include <string>

#include <nlohmann/json.hpp>

#include "access_guard.hpp"
#include "document.hpp"
#include "http_error.hpp"
#include "mesh_slots.hpp"
#include "pdesurf/model.hpp"
#include "root_sandbox.hpp"
// After Eigen (through pdesurf's headers): httplib.h brings <resolv.h>, whose `_res` macro
// breaks Eigen's headers.
#include <httplib.h>

namespace pdesurf::studio {

using Handler = std::function<void(const httplib::Request&, httplib::Response&)>;

inline constexpr std::uint32_t kMinResolution = 2, kMaxMeshResolution = 257,
                               kMaxExportResolution = 4097;
inline constexpr std::uint32_t kDefaultMeshResolution = 16, kDefaultExportResolution = 33;

/// What the routes work on. Every handler runs through guarded(): one lock for all, so
/// edits, solves and file writes are serialised and no HTTP thread sees a half-applied
/// change.
struct Studio {
  httplib::Server& server;
  Document& document;
  MeshSlots& meshes;
  const RootSandbox& sandbox;
  const AccessGuard& access;
  std::mutex& mutex;

  /// Refuses what AccessGuard::refusal refuses (the body is read by now), locks, and turns
  /// HttpError, ModelError and other exceptions into JSON errors.
  Handler guarded(Handler handler) const;
};

void addModelRoutes(const Studio& studio);
void addSurfaceRoutes(const Studio& studio);
void addFileRoutes(const Studio& studio);

// ---------------------------------------------------------------------------------------
// Shared by the routes

void sendJson(httplib::Response& res, const nlohmann::json& body, int status = 200);
/// The request body as a JSON object (400 otherwise).
nlohmann::json bodyObject(const httplib::Request& req);
/// A string member of a request's JSON object (400 naming it otherwise).
std::string stringMember(const nlohmann::json& doc, const std::string& name);
/// A whole non-negative decimal number in [lo, hi] (400 naming `what` otherwise).
std::uint32_t parseUint(const std::string& text, std::uint32_t lo, std::uint32_t hi,
                        const std::string& what);

/// The solver a request names (`solver=global|local`, `seed=K`: the local solver's seed
/// frame of a vertex-frame model), 400 naming the bad one.
SolveOptions solveOptions(const httplib::Request& req, const Document& document);

/// What a mesh request asks for (GET /api/mesh, or an edit with `?mesh=1`).
struct MeshRequest {
  std::uint32_t resolution = kDefaultMeshResolution;
  std::uint64_t base = 0;  // X-Mesh-Id of the client's mesh at this resolution, 0: none
  SolveOptions options;
};

/// Reads a mesh request's parameters (400 naming the bad one), before anything changes.
MeshRequest meshRequest(const httplib::Request& req, const Document& document);

/// Answers with the surface mesh of the open model (MeshSlots::mesh) and its headers.
void sendMesh(const Studio& studio, const MeshRequest& request, httplib::Response& res);

/// A binary answer computed for this revision (X-Revision: the page matches it to its mesh).
void sendBinary(httplib::Response& res, std::string bytes, std::uint64_t revision);

}  // namespace pdesurf::studio
