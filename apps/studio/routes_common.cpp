// What the studio's routes share (routes.hpp).
#include <charconv>
#include <limits>
#include <optional>
#include <system_error>

#include <fmt/format.h>

#include "routes.hpp"

namespace pdesurf::studio {

using Json = nlohmann::json;

Handler Studio::guarded(Handler handler) const {
  return [this, handler = std::move(handler)](const httplib::Request& req, httplib::Response& res) {
    try {
      if (const std::optional<HttpError> refused = access.refusal(req))
        fail(refused->status, refused->message);
      std::lock_guard lock(mutex);
      handler(req, res);
    } catch (const HttpError& e) {
      sendJson(res, {{"error", e.message}}, e.status);
    } catch (const FileError& e) {  // the server's own files (autosaves, saves)
      sendJson(res, {{"error", e.what()}}, 500);
    } catch (const Error& e) {  // what the request asked is bad input to the library
      sendJson(res, {{"error", e.what()}}, 400);
    } catch (const std::exception& e) {
      sendJson(res, {{"error", e.what()}}, 500);
    }
  };
}

void sendJson(httplib::Response& res, const Json& body, int status) {
  res.status = status;
  res.set_content(body.dump(), "application/json");
}

Json bodyObject(const httplib::Request& req) {
  Json doc = Json::parse(req.body, nullptr, false);
  if (doc.is_discarded()) fail(400, "$: malformed JSON");
  if (!doc.is_object()) fail(400, fmt::format("$: expected an object, found {}", doc.type_name()));
  return doc;
}

std::string stringMember(const Json& doc, const std::string& name) {
  auto it = doc.find(name);
  if (it == doc.end()) fail(400, fmt::format("$: missing \"{}\"", name));
  if (!it->is_string())
    fail(400, fmt::format("$.{}: expected a string, found {}", name, it->type_name()));
  return it->get<std::string>();
}

std::uint32_t parseUint(const std::string& text, std::uint32_t lo, std::uint32_t hi,
                        const std::string& what) {
  std::uint32_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || value < lo || value > hi)
    fail(400, fmt::format("{}: expected a whole number from {} to {}, found \"{}\"", what, lo, hi,
                          text));
  return value;
}

SolveOptions solveOptions(const httplib::Request& req, const Document& document) {
  SolveOptions o;
  if (req.has_param("solver")) {
    const std::string s = req.get_param_value("solver");
    if (s == "local")
      o.vertexFrames.solver = Solver::Local;
    else if (s != "global")
      fail(400, fmt::format("solver: expected \"global\" or \"local\", found \"{}\"", s));
  }
  const ModelSession& session = document.session();
  if (req.has_param("seed") && session.hasEditableParts()) {
    const auto frames = static_cast<std::uint32_t>(session.frames()->frames.size());
    o.vertexFrames.seedFrame = parseUint(req.get_param_value("seed"), 0, frames - 1, "seed");
  }
  return o;
}

MeshRequest meshRequest(const httplib::Request& req, const Document& document) {
  MeshRequest m;
  if (req.has_param("resolution"))
    m.resolution = parseUint(req.get_param_value("resolution"), kMinResolution, kMaxMeshResolution,
                             "resolution");
  if (req.has_param("base"))
    m.base = parseUint(req.get_param_value("base"), 1, std::numeric_limits<std::uint32_t>::max(),
                       "base");
  m.options = solveOptions(req, document);
  return m;
}

void sendMesh(const Studio& studio, const MeshRequest& request, httplib::Response& res) {
  Document& doc = studio.document;
  MeshAnswer mesh = studio.meshes.mesh(doc.session(), doc.revision(), request.resolution,
                                       request.base, request.options);
  res.set_content(std::move(mesh.bytes), "application/octet-stream");
  if (mesh.base != 0) res.set_header("X-Mesh-Base", std::to_string(mesh.base));
  res.set_header("X-Mesh-Id", std::to_string(mesh.id));
  res.set_header("X-Solve-Ms", fmt::format("{:.3f}", mesh.solveMs));
  res.set_header("X-Tessellate-Ms", fmt::format("{:.3f}", mesh.tessellateMs));
  res.set_header("X-C0-Gap", fmt::format("{}", mesh.c0Gap));
}

void sendBinary(httplib::Response& res, std::string bytes, std::uint64_t revision) {
  res.set_content(std::move(bytes), "application/octet-stream");
  res.set_header("X-Revision", std::to_string(revision & 0xffffffffu));
}

}  // namespace pdesurf::studio
