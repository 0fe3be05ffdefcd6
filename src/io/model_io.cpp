// Parsing, validation and writing of vertex-frame model files.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "io/json_reader.hpp"
#include "io/json_writer.hpp"
#include "io/middle_mismatch.hpp"
#include "pdesurf/model_io.hpp"

namespace pdesurf {

using detail::Json;
using detail::Reader;
using detail::sideName;
using detail::typeName;

VertexFrameModel parseVertexFrameModel(std::string_view text, const std::string& source) {
  const Reader rd(source);
  return detail::parseVertexFrameDocument(rd.parseDocument(text), rd);
}

VertexFrameModel detail::parseVertexFrameDocument(const Json& doc, const Reader& rd) {
  rd.expectObject(doc, "$");
  const Json& type = rd.member(doc, "$", "type");
  if (!type.is_string())
    rd.fail("$.type", fmt::format("expected a string, found {}", typeName(type)));
  if (type.get<std::string>() != "vertex-frames")
    rd.fail("$.type", fmt::format("unknown model type \"{}\" (this reader takes \"vertex-frames\")",
                                  type.get<std::string>()));

  VertexFrameModel model;
  if (auto it = doc.find("name"); it != doc.end()) {
    if (!it->is_string())
      rd.fail("$.name", fmt::format("expected a string, found {}", typeName(*it)));
    model.name = it->get<std::string>();
  }

  const Json& verts = rd.member(doc, "$", "vertices");
  rd.expectArray(verts, "$.vertices", 1);
  model.vertices.reserve(verts.size());
  for (std::size_t i = 0; i < verts.size(); ++i)
    model.vertices.push_back(rd.vec3(verts[i], fmt::format("$.vertices[{}]", i)));

  const Json& frames = rd.member(doc, "$", "frames");
  rd.expectArray(frames, "$.frames", 1);
  model.frames.resize(frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const std::string path = fmt::format("$.frames[{}]", k);
    const Json& jf = frames[k];
    rd.expectObject(jf, path);
    Frame& f = model.frames[k];
    const Json& fv = rd.member(jf, path, "vertices");
    if (!fv.is_array() || fv.size() != 8)
      rd.fail(path + ".vertices",
              fv.is_array()
                  ? fmt::format("a frame has 8 vertices (P1..P8), found {}", fv.size())
                  : fmt::format("expected an array of 8 vertex indices, found {}", typeName(fv)));
    for (int i = 0; i < 8; ++i)
      f.vertices[i] = rd.index(fv[i], fmt::format("{}.vertices[{}]", path, i),
                               model.vertices.size(), "vertex", "vertices");
    if (auto it = jf.find("a1"); it != jf.end()) f.a1 = rd.vec3(*it, path + ".a1");
    if (auto it = jf.find("a2"); it != jf.end()) f.a2 = rd.vec3(*it, path + ".a2");
    if (auto it = jf.find("forces"); it != jf.end())
      f.forces = rd.frameForces(*it, path + ".forces", f, static_cast<std::uint32_t>(k));
  }

  if (auto it = doc.find("forces"); it != doc.end())
    model.forces = rd.sharedForces(*it, "$.forces", model);

  const FrameTopology topo = buildTopology(model);
  if (topo.error.kind == TopologyError::Kind::MiddleVertexDiffers) {
    const FrameSide a = topo.error.first, b = topo.error.second;
    const detail::MiddleMismatch m = detail::middleMismatch(model, topo.error);
    rd.fail(fmt::format("$.frames[{}].vertices", b.frame),
            fmt::format("its edge {} shares corner vertices {} and {} with edge {} of frames[{}], "
                        "but its middle vertex is {} where frames[{}] has {}: frames that share "
                        "an edge share all three of its vertices",
                        sideName(b.side), m.corner0, m.corner1, sideName(a.side), a.frame,
                        m.middleSecond, a.frame, m.middleFirst));
  }
  return model;
}

VertexFrameModel loadVertexFrameModel(const std::string& path) {
  return parseVertexFrameModel(detail::readModelFile(path), path);
}

std::string serializeVertexFrameModel(const VertexFrameModel& model) {
  using detail::jsonOf;
  detail::ModelJson doc;
  doc["type"] = "vertex-frames";
  if (!model.name.empty()) doc["name"] = model.name;
  doc["vertices"] = jsonOf(model.vertices);
  doc["frames"] = detail::ModelJson::array();
  for (const Frame& f : model.frames) {
    detail::ModelJson frame;
    frame["vertices"] = f.vertices;
    if (f.a1 != Vec3::Ones()) frame["a1"] = jsonOf(f.a1);
    if (f.a2 != Vec3::Ones()) frame["a2"] = jsonOf(f.a2);
    for (const FrameForce& force : f.forces) {
      const Region& r = force.region;
      frame["forces"].push_back({{"f0", jsonOf(force.f0)}, {"region", {r.u0, r.u1, r.v0, r.v1}}});
    }
    doc["frames"].push_back(std::move(frame));
  }
  for (const SharedForce& force : model.forces)
    doc["forces"].push_back({{"f0", jsonOf(force.f0)}, {"frames", force.frames}});
  return detail::writeModelJson(doc);
}

namespace {

using detail::ModelJson;

/// `out` (the written value at one key path) with the fields of `in` (the original file's
/// value at that path) that `known` (the writer's text of the original's model there) lacks:
/// fields the method does not hold, in `in`'s key order (the keys only `out` has follow).
/// Array elements are matched by identity: an element of `out` takes the unknown fields of
/// the original element the writer wrote exactly as `out` holds it (unchanged, wherever it
/// moved), else, when both arrays are as long, of the element at its index.
ModelJson mergeUnknown(const ModelJson& out, const ModelJson& in, const ModelJson* known) {
  if (out.is_object() && in.is_object()) {
    ModelJson merged = ModelJson::object();
    for (const auto& [key, value] : in.items()) {
      const ModelJson* k = known && known->contains(key) ? &(*known)[key] : nullptr;
      if (out.contains(key))
        merged[key] = mergeUnknown(out[key], value, k);
      else if (!k)
        merged[key] = value;  // a field the method does not hold
      // else: a field the method holds and no longer writes (the edit removed it)
    }
    for (const auto& [key, value] : out.items())
      if (!merged.contains(key)) merged[key] = value;
    return merged;
  }
  // Only arrays of objects hold fields (points and indices do not).
  const auto holdsObjects = [](const ModelJson& a) {
    return std::any_of(a.begin(), a.end(), [](const ModelJson& e) { return e.is_object(); });
  };
  if (out.is_array() && in.is_array() && known && known->is_array() && known->size() == in.size() &&
      holdsObjects(in)) {
    ModelJson merged = out;
    std::vector<bool> taken(in.size(), false);
    for (std::size_t j = 0; j < out.size(); ++j) {
      // The element at the same index first: an array an edit left alone matches in one pass.
      std::size_t match = j < in.size() && !taken[j] && (*known)[j] == out[j] ? j : in.size();
      for (std::size_t i = 0; i < in.size() && match == in.size(); ++i)
        if (!taken[i] && (*known)[i] == out[j]) match = i;
      if (match == in.size() && out.size() == in.size() && !taken[j]) match = j;
      if (match == in.size()) continue;
      taken[match] = true;
      merged[j] = mergeUnknown(out[j], in[match], &(*known)[match]);
    }
    return merged;
  }
  return out;
}

}  // namespace

std::string keepUnknownFields(const std::string& written, std::string_view original) {
  const ModelJson in = ModelJson::parse(original, nullptr, false);
  if (in.is_discarded() || !in.is_object()) return written;
  ModelJson known;
  try {
    known = ModelJson::parse(serializeModel(parseModel(original, "original")));
  } catch (const ModelError&) {
    return written;  // not a model file: nothing is known to be unknown
  }
  const ModelJson out = ModelJson::parse(written);
  const ModelJson merged = mergeUnknown(out, in, &known);
  if (merged == out) return written;  // no unknown fields: the writer's text as it is
  std::string text = detail::writeModelJson(merged);
  // The fields kept must not change the model (a field a method reads only in some forms).
  try {
    if (serializeModel(parseModel(text, "merged")) == serializeModel(parseModel(written, "w")))
      return text;
  } catch (const ModelError&) {
  }
  return written;
}

}  // namespace pdesurf
