// Model files of any type (include/pdesurf/model_io.hpp): the "type" picks the parser that
// sits beside its type's other file code (model_io.cpp, spectral_io.cpp, bspline_pde_io.cpp).
#include <fmt/format.h>

#include "io/model_reader.hpp"
#include "pdesurf/bspline_pde_io.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/spectral_io.hpp"

namespace pdesurf {

AnyModel parseModel(std::string_view text, const std::string& source) {
  const detail::ModelReader rd(source);
  const detail::Json doc = rd.parseDocument(text);
  rd.expectObject(doc, "$");
  const std::string type = rd.string(rd.member(doc, "$", "type"), "$.type");
  if (type == "vertex-frames") return detail::parseVertexFrameDocument(doc, rd);
  if (type == "spectral") return detail::parseSpectralDocument(doc, source);
  if (type == "cross-sections") return detail::parseCrossSectionsDocument(doc, source);
  if (type == "bspline-pde") return detail::parseBSplinePdeDocument(doc, source);
  rd.fail("$.type",
          fmt::format("unknown model type \"{}\" (expected \"vertex-frames\", \"spectral\", "
                      "\"cross-sections\" or \"bspline-pde\")",
                      type));
}

AnyModel loadModel(const std::string& path) {
  return parseModel(detail::readModelFile(path), path);
}

SolvedModel loadAndSolve(const std::string& path, const SolveOptions& options) {
  return solveModel(loadModel(path), path, options);
}

std::string serializeModel(const AnyModel& model) {
  return std::visit(
      [](const auto& m) -> std::string {
        using T = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<T, VertexFrameModel>)
          return serializeVertexFrameModel(m);
        else
          return serializeModel(m);
      },
      model);
}

}  // namespace pdesurf
