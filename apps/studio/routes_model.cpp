// The studio's routes of the model and its edits (routes.hpp): GET /api/model, POST /api/edit,
// /api/transform, /api/end-group, /api/undo, /api/redo.
#include <optional>

#include <fmt/format.h>

#include "pdesurf/edit_io.hpp"
#include "pdesurf/model_io.hpp"
#include "routes.hpp"

namespace pdesurf::studio {

using Json = nlohmann::json;

void addModelRoutes(const Studio& studio) {
  Document& doc = studio.document;

  studio.server.Get("/api/model",
                    studio.guarded([&doc](const httplib::Request&, httplib::Response& res) {
                      Json out = doc.openedStatus();
                      out["type"] = modelTypeName(doc.session().model());
                      out["hasEditableParts"] = doc.session().hasEditableParts();
                      out["model"] = Json::parse(doc.modelText());
                      // What the page draws and shows of it: no model file read there.
                      if (!doc.session().hasEditableParts()) out.update(doc.shapeParts());
                      sendJson(res, out);
                    }));

  studio.server.Post("/api/edit", studio.guarded([&studio, &doc](const httplib::Request& req,
                                                                 httplib::Response& res) {
    // Every type's edits through one parse and one apply (its method's: edit_io.hpp).
    ModelSession& session = doc.session();
    const ModelEdit edit = parseEdit(req.body, session.model());
    // `?mesh=1` (and the mesh's parameters): the mesh after the edit, with the status in
    // X-Status: one round trip for a drag step instead of two.
    std::optional<MeshRequest> mesh;
    if (req.has_param("mesh")) {
      if (req.get_param_value("mesh") != "1")
        fail(400, fmt::format("mesh: expected 1, found \"{}\"", req.get_param_value("mesh")));
      mesh = meshRequest(req, doc);
    }
    session.apply(edit);
    doc.autosave();
    if (mesh) {
      sendMesh(studio, *mesh, res);
      res.set_header("X-Status", doc.status().dump());
    } else {
      sendJson(res, doc.status());
    }
  }));

  // Moves, turns or scales the whole model, of any type: one undo step.
  studio.server.Post("/api/transform",
                     studio.guarded([&doc](const httplib::Request& req, httplib::Response& res) {
                       doc.session().transform(parseTransform(req.body));
                       doc.autosave();
                       sendJson(res, doc.status());
                     }));

  studio.server.Post("/api/end-group",
                     studio.guarded([&doc](const httplib::Request&, httplib::Response& res) {
                       doc.session().endGroup();
                       sendJson(res, doc.status());
                     }));

  studio.server.Post("/api/undo",
                     studio.guarded([&doc](const httplib::Request&, httplib::Response& res) {
                       if (!doc.session().undo()) fail(409, "nothing to undo");
                       doc.autosave();
                       sendJson(res, doc.status());
                     }));

  studio.server.Post("/api/redo",
                     studio.guarded([&doc](const httplib::Request&, httplib::Response& res) {
                       if (!doc.session().redo()) fail(409, "nothing to redo");
                       doc.autosave();
                       sendJson(res, doc.status());
                     }));
}

}  // namespace pdesurf::studio
