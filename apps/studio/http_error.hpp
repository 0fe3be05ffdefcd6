// A request the studio cannot serve: its status and the message of {"error": ...}. Thrown by
// the routes and the root sandbox, answered by the server's guard (server.cpp).
#pragma once

#include <string>

namespace pdesurf::studio {

struct HttpError {
  int status;
  std::string message;
};

[[noreturn]] inline void fail(int status, std::string message) {
  throw HttpError{status, std::move(message)};
}

}  // namespace pdesurf::studio
