// Parsing of the studio's questions about a patch's points (edit_io.hpp: parsePatchQuery).
#include <fmt/format.h>

#include "io/json_reader.hpp"
#include "pdesurf/edit_io.hpp"

namespace pdesurf {

using detail::Json;
using detail::Reader;

PatchQuery parsePatchQuery(std::string_view json, std::size_t frames, bool withPoints) {
  const Reader rd("patch query");
  const Json doc = rd.parseDocument(json);
  rd.expectObject(doc, "$");
  PatchQuery out;
  out.frame = rd.index(rd.member(doc, "$", "frame"), "$.frame", frames, "frame", "frames");
  const char* key = withPoints ? "points" : "uv";
  const Json& list = rd.member(doc, "$", key);
  const std::string path = fmt::format("$.{}", key);
  rd.expectArray(list, path, 1);
  if (list.size() > PatchQuery::kMaxPoints)
    rd.fail(path, fmt::format("at most {} entries, found {}", PatchQuery::kMaxPoints, list.size()));
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string at = fmt::format("{}[{}]", path, i);
    if (withPoints) {
      out.points.push_back(rd.vec3(list[i], at));
      continue;
    }
    const auto uv = rd.numbers<2>(list[i], at);
    for (int c = 0; c < 2; ++c)
      if (uv[c] < 0.0 || uv[c] > 1.0)
        rd.fail(fmt::format("{}[{}]", at, c),
                fmt::format("a parameter must lie in [0, 1], found {}", uv[c]));
    out.uv.push_back(uv);
  }
  return out;
}

}  // namespace pdesurf
