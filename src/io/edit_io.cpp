// Parsing and validation of studio edits (include/pdesurf/edit_io.hpp).
#include "pdesurf/edit_io.hpp"
#include "io/json_reader.hpp"

namespace pdesurf {

namespace {

using detail::Json;
using detail::Reader;

/// With new a1, a2 a frame's own forces and the shared forces on it must stay solvable.
void checkFrameStaysSolvable(const Reader& rd, const VertexFrameModel& model, const Frame& f,
                             std::uint32_t k, const std::string& path) {
  for (const FrameForce& force : f.forces)
    rd.checkSolvable(f, force.f0, force.region, path, k, false);
  for (const SharedForce& force : model.forces)
    for (std::uint32_t listed : force.frames)
      if (listed == k) rd.checkSolvable(f, force.f0, Region{}, path, k, true);
}

}  // namespace

GroupedEdit parseEdit(std::string_view json, const VertexFrameModel& model) {
  const Reader rd("edit");
  const Json doc = rd.parseDocument(json);
  rd.expectObject(doc, "$");
  GroupedEdit out;
  if (auto it = doc.find("group"); it != doc.end()) {
    if (!it->is_string())
      rd.fail("$.group", fmt::format("expected a string, found {}", detail::typeName(*it)));
    out.group = it->get<std::string>();
  }
  const Json& op = rd.member(doc, "$", "op");
  if (!op.is_string())
    rd.fail("$.op", fmt::format("expected a string, found {}", detail::typeName(op)));
  const std::string name = op.get<std::string>();

  if (name == "move-vertex") {
    MoveVertex e;
    e.vertex = rd.index(rd.member(doc, "$", "vertex"), "$.vertex", model.vertices.size(), "vertex",
                        "vertices");
    e.position = rd.vec3(rd.member(doc, "$", "position"), "$.position");
    out.edit = e;
  } else if (name == "set-parameters") {
    SetParameters e;
    const Json& frames = rd.member(doc, "$", "frames");
    rd.expectArray(frames, "$.frames", 1);
    for (std::size_t i = 0; i < frames.size(); ++i)
      e.frames.push_back(rd.index(frames[i], fmt::format("$.frames[{}]", i), model.frames.size(),
                                  "frame", "frames"));
    if (auto it = doc.find("a1"); it != doc.end()) e.a1 = rd.vec3(*it, "$.a1");
    if (auto it = doc.find("a2"); it != doc.end()) e.a2 = rd.vec3(*it, "$.a2");
    if (!e.a1 && !e.a2) rd.fail("$", "set-parameters needs \"a1\", \"a2\" or both");
    for (std::uint32_t k : e.frames) {
      Frame f = model.frames[k];
      if (e.a1) f.a1 = *e.a1;
      if (e.a2) f.a2 = *e.a2;
      checkFrameStaysSolvable(rd, model, f, k, "$");
    }
    out.edit = std::move(e);
  } else if (name == "set-forces") {
    SetFrameForces e;
    e.frame =
        rd.index(rd.member(doc, "$", "frame"), "$.frame", model.frames.size(), "frame", "frames");
    e.forces =
        rd.frameForces(rd.member(doc, "$", "forces"), "$.forces", model.frames[e.frame], e.frame);
    out.edit = std::move(e);
  } else if (name == "set-shared-forces") {
    SetSharedForces e;
    e.forces = rd.sharedForces(rd.member(doc, "$", "forces"), "$.forces", model);
    out.edit = std::move(e);
  } else {
    rd.fail("$.op", fmt::format("unknown edit \"{}\" (known: move-vertex, set-parameters, "
                                "set-forces, set-shared-forces)",
                                name));
  }
  return out;
}

}  // namespace pdesurf
