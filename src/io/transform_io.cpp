// Parsing and checking whole-model transforms as the studio sends them
// (include/pdesurf/edit_io.hpp: parseTransform, checkTransform).
#include <numbers>
#include <stdexcept>

#include "io/json_reader.hpp"
#include "pdesurf/edit_io.hpp"
#include "pdesurf/error.hpp"
#include "pdesurf/method.hpp"

namespace pdesurf {

namespace {

using detail::Json;
using detail::Reader;

/// Builds one part of the map; the library's refusal (zero axis, scale ≤ 0) becomes a
/// ModelError at `path`.
template <typename Make>
AffineMap part(const Reader& rd, const std::string& path, Make make) {
  try {
    AffineMap map = make();
    map.validate();
    return map;
  } catch (const InvalidArgument& e) {
    rd.fail(path, e.what());
  }
}

}  // namespace

AffineMap parseTransform(std::string_view json) {
  const Reader rd("transform");
  const Json doc = rd.parseDocument(json);
  rd.expectObject(doc, "$");
  for (const auto& [key, value] : doc.items())
    if (key != "translate" && key != "rotate" && key != "scale" && key != "center")
      rd.fail("$", fmt::format("unknown field \"{}\" (expected \"translate\", \"rotate\", "
                               "\"scale\" or \"center\")",
                               key));
  const Vec3 center = doc.contains("center") ? rd.vec3(doc.at("center"), "$.center") : Vec3::Zero();
  AffineMap map;
  bool any = false;
  if (auto it = doc.find("scale"); it != doc.end()) {
    const double s = rd.number(*it, "$.scale");
    map = part(rd, "$.scale", [&] { return AffineMap::scalingAbout(s, center); }) * map;
    any = true;
  }
  if (auto it = doc.find("rotate"); it != doc.end()) {
    const Json& r = *it;
    rd.expectObject(r, "$.rotate");
    for (const auto& [key, value] : r.items())
      if (key != "axis" && key != "degrees" && key != "center")
        rd.fail("$.rotate", fmt::format("unknown field \"{}\" (expected \"axis\", \"degrees\" or "
                                        "\"center\")",
                                        key));
    const Vec3 axis = rd.vec3(rd.member(r, "$.rotate", "axis"), "$.rotate.axis");
    const double degrees = rd.number(rd.member(r, "$.rotate", "degrees"), "$.rotate.degrees");
    const Vec3 about = r.contains("center") ? rd.vec3(r.at("center"), "$.rotate.center") : center;
    map = part(rd, "$.rotate.axis",
               [&] {
                 return AffineMap::rotationAbout(axis, degrees * std::numbers::pi / 180.0, about);
               }) *
          map;
    any = true;
  }
  if (auto it = doc.find("translate"); it != doc.end()) {
    const Vec3 t = rd.vec3(*it, "$.translate");
    map = AffineMap::translationBy(t) * map;
    any = true;
  }
  if (!any) rd.fail("$", "a transform needs \"translate\", \"rotate\" or \"scale\"");
  return map;
}

void checkTransform(const VertexFrameModel& model, const AffineMap& map) {
  const Reader rd("transform");
  for (std::size_t k = 0; k < model.frames.size(); ++k) {
    const Frame& f = model.frames[k];
    for (std::size_t i = 0; i < f.forces.size(); ++i)
      rd.checkSolvable(f, map.vector(f.forces[i].f0), f.forces[i].region,
                       fmt::format("$.frames[{}].forces[{}]", k, i), static_cast<std::uint32_t>(k),
                       false);
  }
  for (std::size_t i = 0; i < model.forces.size(); ++i)
    for (std::uint32_t k : model.forces[i].frames)
      rd.checkSolvable(model.frames[k], map.vector(model.forces[i].f0), Region{},
                       fmt::format("$.forces[{}]", i), k, true);
}

void checkTransform(const AnyModel& model, const AffineMap& map) {
  model.method().checkTransform(model, map);
}

}  // namespace pdesurf
