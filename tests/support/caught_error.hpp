// What a call throws, caught as the base every library error derives from (pdesurf::Error).
#pragma once

#include <gtest/gtest.h>

#include <exception>
#include <optional>
#include <string>
#include <typeinfo>

#include "pdesurf/error.hpp"

namespace pdesurf::testing {

/// The parts of an Error a call threw, and whether it was of the kind `Kind` as well.
struct CaughtError {
  std::string file, jsonPath, message, what;
  bool ofKind = false;
};

/// Runs `call` and returns the Error it threw; a call that returns, or throws anything that
/// is not a pdesurf::Error, fails the test (naming the exception's type) and gives nullopt.
template <class Kind, class Call>
std::optional<CaughtError> caughtError(Call&& call) {
  try {
    call();
  } catch (const Error& e) {
    return CaughtError{e.file(), e.jsonPath(), e.message(), e.what(),
                       dynamic_cast<const Kind*>(&e) != nullptr};
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw " << typeid(e).name() << ", not a pdesurf::Error: " << e.what();
    return std::nullopt;
  }
  ADD_FAILURE() << "threw nothing";
  return std::nullopt;
}

}  // namespace pdesurf::testing
