// Model files of any type (include/pdesurf/model_io.hpp): the "type" picks the method
// (method.hpp) whose description parses and writes the document.
#include <fmt/format.h>

#include "io/model_reader.hpp"
#include "pdesurf/method.hpp"
#include "pdesurf/model_io.hpp"

namespace pdesurf {

namespace {

/// "\"a\", \"b\" or \"c\"": every registered type, for the unknown-type message.
std::string typeList() {
  const std::vector<const SurfaceMethod*> methods = surfaceMethods();
  std::string out;
  for (std::size_t i = 0; i < methods.size(); ++i) {
    if (i > 0) out += i + 1 == methods.size() ? " or " : ", ";
    out += fmt::format("\"{}\"", methods[i]->typeName());
  }
  return out;
}

}  // namespace

AnyModel parseModel(std::string_view text, const std::string& source) {
  const detail::ModelReader rd(source);
  const detail::Json doc = rd.parseDocument(text);
  rd.expectObject(doc, "$");
  const std::string type = rd.string(rd.member(doc, "$", "type"), "$.type");
  if (const SurfaceMethod* method = findMethod(type)) return method->parse(doc, source);
  rd.fail("$.type", fmt::format("unknown model type \"{}\" (expected {})", type, typeList()));
}

AnyModel loadModel(const std::string& path) {
  return parseModel(detail::readModelFile(path), path);
}

std::string serializeModel(const AnyModel& model) { return model.method().serialize(model); }

}  // namespace pdesurf
