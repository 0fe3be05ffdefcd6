// The registry of surface methods (include/pdesurf/method.hpp): the built-in table, then the
// methods a program registers. No static registration: the built-in table is a function's
// list, and extra methods arrive through registerMethod.
#include <mutex>
#include <shared_mutex>
#include <stdexcept>

#include <fmt/format.h>

#include "methods/builtin.hpp"
#include "pdesurf/error.hpp"

namespace pdesurf {

namespace {

struct Registry {
  std::shared_mutex mutex;
  std::vector<const SurfaceMethod*> added;
};

Registry& registry() {
  static Registry instance;
  return instance;
}

/// The built-in methods, in the order surfaceMethods() lists them.
const std::vector<const SurfaceMethod*>& builtinMethods() {
  static const std::vector<const SurfaceMethod*> kBuiltin = {
      &detail::vertexFramesMethod(), &detail::spectralMethod(), &detail::crossSectionsMethod(),
      &detail::bsplinePdeMethod()};
  return kBuiltin;
}

/// The first method, built-in then added, for which `matches` holds, else nullptr.
template <class Matches>
const SurfaceMethod* findWhere(Matches matches) {
  for (const SurfaceMethod* method : builtinMethods())
    if (matches(*method)) return method;
  Registry& r = registry();
  const std::shared_lock lock(r.mutex);
  for (const SurfaceMethod* method : r.added)
    if (matches(*method)) return method;
  return nullptr;
}

}  // namespace

void registerMethod(const SurfaceMethod& method) {
  const std::string_view type = method.typeName();
  if (findMethod(type))
    throw InvalidArgument(fmt::format("a method of type \"{}\" is already registered", type));
  if (findWhere([&](const SurfaceMethod& m) { return m.modelType() == method.modelType(); }))
    throw InvalidArgument(
        fmt::format("the model type of method \"{}\" is already another method's", type));
  Registry& r = registry();
  const std::unique_lock lock(r.mutex);
  r.added.push_back(&method);
}

const SurfaceMethod* findMethod(std::string_view typeName) {
  return findWhere([&](const SurfaceMethod& m) { return typeName == m.typeName(); });
}

std::vector<const SurfaceMethod*> surfaceMethods() {
  std::vector<const SurfaceMethod*> all = builtinMethods();
  Registry& r = registry();
  const std::shared_lock lock(r.mutex);
  all.insert(all.end(), r.added.begin(), r.added.end());
  return all;
}

const SurfaceMethod& methodForModelType(const std::type_info& type) {
  const std::type_index index(type);
  // The built-in methods first, without the lock: every model value of theirs asks.
  for (const SurfaceMethod* method : builtinMethods())
    if (method->modelType() == index) return *method;
  if (const SurfaceMethod* method =
          findWhere([&](const SurfaceMethod& m) { return m.modelType() == index; }))
    return *method;
  throw InvalidArgument(
      fmt::format("no surface method is registered for the model type {}", type.name()));
}

}  // namespace pdesurf
