// Who may ask the studio (apps/studio/README.md, "Security"): the per-launch token, the Host
// and Origin values that name this server, and the checks every request passes before any
// route runs.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "http_error.hpp"

namespace httplib {
struct Request;
}

namespace pdesurf::studio {

/// HOST as the authority of a URL: an IPv6 address in brackets.
std::string urlHost(const std::string& host);

class AccessGuard {
 public:
  /// With `requireToken`, a fresh token from the kernel's cryptographic generator (throws
  /// StudioError when it cannot draw one); without, none is asked for (--no-token).
  explicit AccessGuard(bool requireToken);

  /// The token requests must carry, or empty.
  const std::string& token() const { return token_; }

  /// Names this server once it is bound to `host` and `port`: the Host values (lower case)
  /// of its address and port, for a loopback address also localhost (and the reverse), and
  /// the page origins "http://" + each. A web page of another name that resolves to
  /// 127.0.0.1 (DNS rebinding) sends its own name and is refused.
  void bind(const std::string& host, int port);

  /// Why a request is refused before any handler runs, or nothing. Every request needs a
  /// Host naming this server. Except the page's own files (GET and HEAD outside /api/),
  /// a request needs no foreign Origin and the token; a request other than GET and HEAD
  /// (every one that changes something) declares a JSON body, which a browser sends to
  /// another origin only after a preflight this server never grants.
  std::optional<HttpError> refusal(const httplib::Request& req) const;

 private:
  std::string token_;                 // empty: none required (--no-token)
  std::vector<std::string> hosts_;    // the Host values naming this server, lower case
  std::vector<std::string> origins_;  // "http://" + each of hosts_
};

}  // namespace pdesurf::studio
