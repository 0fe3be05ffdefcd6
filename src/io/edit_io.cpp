// Parsing and validation of studio edits (include/pdesurf/edit_io.hpp).
#include "pdesurf/edit_io.hpp"
#include "io/json_reader.hpp"
#include "io/model_reader.hpp"
#include "pdesurf/method.hpp"

#include <optional>

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

/// A list of at least `min` indices into a list of `count` things.
std::vector<std::uint32_t> indices(const Reader& rd, const Json& list, const std::string& path,
                                   std::size_t min, std::size_t count, const char* what,
                                   const char* whats) {
  rd.expectArray(list, path, min);
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i < list.size(); ++i)
    out.push_back(rd.index(list[i], fmt::format("{}[{}]", path, i), count, what, whats));
  return out;
}

/// {"frame": k, "side": s}: a side of a frame, s = 0..3 in the order v = 0, u = 1, v = 1,
/// u = 0 (Side, the order of GET /api/boundaries).
FrameSide frameSide(const Reader& rd, const Json& j, const std::string& path,
                    const VertexFrameModel& model) {
  rd.expectObject(j, path);
  FrameSide out;
  out.frame = rd.index(rd.member(j, path, "frame"), path + ".frame", model.frames.size(), "frame",
                       "frames");
  out.side =
      static_cast<Side>(rd.index(rd.member(j, path, "side"), path + ".side", 4, "side", "sides"));
  return out;
}

std::vector<FrameSide> frameSides(const Reader& rd, const Json& list, const std::string& path,
                                  std::size_t min, const VertexFrameModel& model) {
  rd.expectArray(list, path, min);
  std::vector<FrameSide> out;
  for (std::size_t i = 0; i < list.size(); ++i)
    out.push_back(frameSide(rd, list[i], fmt::format("{}[{}]", path, i), model));
  return out;
}

/// The structure edits (session.hpp); what they would make is checked when applied.
std::optional<Edit> parseStructureEdit(const Reader& rd, const Json& doc, const std::string& name,
                                       const VertexFrameModel& model) {
  const std::size_t nf = model.frames.size(), nv = model.vertices.size();
  if (name == "extrude") {
    ExtrudeEdges e;
    e.edges = frameSides(rd, rd.member(doc, "$", "edges"), "$.edges", 1, model);
    if (auto it = doc.find("distance"); it != doc.end()) {
      e.distance = rd.number(*it, "$.distance");
      if (e.distance < 0.0)
        rd.fail("$.distance", "the distance must be ≥ 0 (0: the frame's width)");
    }
    return e;
  }
  if (name == "add-frame") {
    const auto c =
        indices(rd, rd.member(doc, "$", "corners"), "$.corners", 4, nv, "vertex", "vertices");
    if (c.size() != 4) rd.fail("$.corners", fmt::format("expected 4 corners, found {}", c.size()));
    return AddFrame{{c[0], c[1], c[2], c[3]}};
  }
  if (name == "delete-frames")
    return DeleteFrames{
        indices(rd, rd.member(doc, "$", "frames"), "$.frames", 1, nf, "frame", "frames")};
  if (name == "flip-frames")
    return FlipFrames{
        indices(rd, rd.member(doc, "$", "frames"), "$.frames", 1, nf, "frame", "frames")};
  if (name == "mirror-frames") {
    MirrorFrames e;
    e.frames = indices(rd, rd.member(doc, "$", "frames"), "$.frames", 1, nf, "frame", "frames");
    const Json& axis = rd.member(doc, "$", "axis");
    if (axis != "x" && axis != "y" && axis != "z")
      rd.fail("$.axis", fmt::format("expected \"x\", \"y\" or \"z\", found {}", axis.dump()));
    e.axis = axis == "x" ? 0 : axis == "y" ? 1 : 2;
    if (auto it = doc.find("at"); it != doc.end()) e.at = rd.number(*it, "$.at");
    return e;
  }
  if (name == "split-frame") {
    SplitFrame e;
    // One frame ("frame": k) or several ("frames": [k, ...]).
    if (doc.contains("frames"))
      e.frames = indices(rd, rd.member(doc, "$", "frames"), "$.frames", 1, nf, "frame", "frames");
    else
      e.frames = {rd.index(rd.member(doc, "$", "frame"), "$.frame", nf, "frame", "frames")};
    const Json& parts = rd.member(doc, "$", "parts");
    if (!parts.is_number_integer() ||
        (parts.get<std::int64_t>() != 2 && parts.get<std::int64_t>() != 4))
      rd.fail("$.parts", fmt::format("expected 2 or 4, found {}", parts.dump()));
    if (parts.get<std::int64_t>() == 4) {
      e.acrossU = e.acrossV = true;
    } else {
      const Json& across = rd.member(doc, "$", "across");
      if (across != "u" && across != "v")
        rd.fail("$.across", fmt::format("expected \"u\" or \"v\", found {}", across.dump()));
      e.acrossU = across == "u";
      e.acrossV = across == "v";
    }
    return e;
  }
  if (name == "weld-vertices") {
    const auto v =
        indices(rd, rd.member(doc, "$", "vertices"), "$.vertices", 2, nv, "vertex", "vertices");
    if (v.size() != 2)
      rd.fail("$.vertices", fmt::format("expected 2 vertices, found {}", v.size()));
    return WeldVertices{v[0], v[1]};
  }
  if (name == "weld-edges") {
    const auto e = frameSides(rd, rd.member(doc, "$", "edges"), "$.edges", 2, model);
    if (e.size() != 2) rd.fail("$.edges", fmt::format("expected 2 edges, found {}", e.size()));
    return WeldEdges{e[0], e[1]};
  }
  return std::nullopt;
}

}  // namespace

ModelEdit parseEdit(std::string_view json, const AnyModel& model) {
  return model.method().parseEdit(json, model);
}

GroupedEdit parseFrameEdit(std::string_view json, const VertexFrameModel& model) {
  const detail::ModelReader rd("edit");
  const auto [doc, group, name] = rd.edit(json);
  GroupedEdit out;
  out.group = group;

  if (name == "move-vertex") {
    MoveVertex e;
    e.vertex = rd.index(rd.member(doc, "$", "vertex"), "$.vertex", model.vertices.size(), "vertex",
                        "vertices");
    e.position = rd.vec3(rd.member(doc, "$", "position"), "$.position");
    out.edit = e;
  } else if (name == "move-vertices") {
    MoveVertices e;
    e.vertices = indices(rd, rd.member(doc, "$", "vertices"), "$.vertices", 1,
                         model.vertices.size(), "vertex", "vertices");
    std::vector<std::uint8_t> seen(model.vertices.size(), 0);
    for (std::size_t i = 0; i < e.vertices.size(); ++i)
      if (seen[e.vertices[i]]++)
        rd.fail(fmt::format("$.vertices[{}]", i),
                fmt::format("vertex {} is listed twice", e.vertices[i]));
    const Json& positions = rd.member(doc, "$", "positions");
    rd.expectArray(positions, "$.positions", e.vertices.size());
    if (positions.size() != e.vertices.size())
      rd.fail("$.positions", fmt::format("expected {} positions (one per vertex), found {}",
                                         e.vertices.size(), positions.size()));
    for (std::size_t i = 0; i < positions.size(); ++i)
      e.positions.push_back(rd.vec3(positions[i], fmt::format("$.positions[{}]", i)));
    out.edit = std::move(e);
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
  } else if (auto structure = parseStructureEdit(rd, doc, name, model)) {
    out.edit = std::move(*structure);
  } else {
    rd.fail("$.op",
            fmt::format("unknown edit \"{}\" (known: move-vertex, move-vertices, "
                        "set-parameters, set-forces, set-shared-forces, extrude, add-frame, "
                        "delete-frames, split-frame, weld-vertices, weld-edges, "
                        "flip-frames, mirror-frames)",
                        name));
  }
  return out;
}

NewModelOptions parseNewModel(std::string_view json) {
  const Reader rd("new model");
  const Json doc = rd.parseDocument(json);
  rd.expectObject(doc, "$");
  NewModelOptions out;
  const Json& kind = rd.member(doc, "$", "kind");
  if (kind == "single")
    out.kind = NewModelOptions::Kind::Single;
  else if (kind == "grid")
    out.kind = NewModelOptions::Kind::Grid;
  else if (kind == "tube")
    out.kind = NewModelOptions::Kind::Tube;
  else
    rd.fail("$.kind",
            fmt::format("expected \"single\", \"grid\" or \"tube\", found {}", kind.dump()));
  const auto count = [&](const char* key, std::uint32_t& to) {
    if (auto it = doc.find(key); it != doc.end())
      to = rd.index(*it, fmt::format("$.{}", key), NewModelOptions::kMaxFrames + 1, "frame count",
                    "frame counts");
  };
  count("u", out.u);
  count("v", out.v);
  if (auto it = doc.find("size"); it != doc.end()) out.size = rd.number(*it, "$.size");
  if (auto it = doc.find("name"); it != doc.end()) {
    if (!it->is_string())
      rd.fail("$.name", fmt::format("expected a string, found {}", detail::typeName(*it)));
    out.name = it->get<std::string>();
  }
  newFrameModel(out);  // the counts and size checked where they are used
  return out;
}

}  // namespace pdesurf
