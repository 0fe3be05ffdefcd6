// Who may ask the studio (access_guard.hpp; apps/studio/README.md, "Security").
#include "access_guard.hpp"

#include <sys/random.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include <fmt/format.h>

#include <httplib.h>

#include "server.hpp"

namespace pdesurf::studio {
namespace {

/// The per-launch token's size: 192 bits, as Jupyter's (the issue asks for at least 128).
constexpr std::size_t kTokenBytes = 24;
/// The longest piece of a refused request's header quoted back in the error message.
constexpr std::size_t kQuotedHeaderChars = 80;

/// kTokenBytes from the kernel's cryptographic generator (getrandom(2), which waits only
/// until the pool is first seeded at boot), as lower-case hex.
std::string randomToken() {
  unsigned char bytes[kTokenBytes];
  for (std::size_t done = 0; done < sizeof bytes;) {
    const ssize_t n = ::getrandom(bytes + done, sizeof bytes - done, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw StudioError(fmt::format("cannot draw the studio's token: getrandom: {}",
                                    std::strerror(n < 0 ? errno : EIO)));
    done += static_cast<std::size_t>(n);
  }
  std::string hex;
  for (const unsigned char b : bytes) hex += fmt::format("{:02x}", b);
  return hex;
}

/// Whether `a` equals the secret `b`, in a time that depends only on the lengths (the
/// token's length is no secret): a guess learns nothing from how long the answer takes.
bool sameSecret(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  volatile unsigned char diff = 0;  // volatile: no early exit once a byte differs
  for (std::size_t i = 0; i < a.size(); ++i) diff = diff | static_cast<unsigned char>(a[i] ^ b[i]);
  return diff == 0;
}

std::string lowerCase(std::string_view text) {
  std::string out(text);
  for (char& c : out)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return out;
}

/// A header value as an error message quotes it: at most kQuotedHeaderChars.
std::string quoted(const std::string& value) {
  return fmt::format("\"{}{}\"", value.substr(0, kQuotedHeaderChars),
                     value.size() > kQuotedHeaderChars ? "..." : "");
}

}  // namespace

std::string urlHost(const std::string& host) {
  return host.find(':') != std::string::npos ? "[" + host + "]" : host;
}

AccessGuard::AccessGuard(bool requireToken) : token_(requireToken ? randomToken() : "") {}

void AccessGuard::bind(const std::string& boundHost, int port) {
  const std::string host = lowerCase(boundHost);
  std::vector<std::string> names = {urlHost(host)};
  if (host == "127.0.0.1" || host == "::1") names.push_back("localhost");
  if (host == "localhost") names.insert(names.end(), {"127.0.0.1", "[::1]"});
  hosts_.clear();
  origins_.clear();
  for (const std::string& name : names) {
    const std::string authority = fmt::format("{}:{}", name, port);
    hosts_.push_back(authority);
    origins_.push_back("http://" + authority);
    if (port == 80) {  // the default port may be left out of Host and Origin
      hosts_.push_back(name);
      origins_.push_back("http://" + name);
    }
  }
}

std::optional<HttpError> AccessGuard::refusal(const httplib::Request& req) const {
  // Exactly one `name` header, its value (any case) one of `allowed`.
  const auto oneOf = [&req](const char* name, const std::vector<std::string>& allowed) {
    return req.get_header_value_count(name) == 1 &&
           std::find(allowed.begin(), allowed.end(), lowerCase(req.get_header_value(name))) !=
               allowed.end();
  };
  if (!oneOf("Host", hosts_))
    return HttpError{403, fmt::format("request refused: Host {} is not this studio's address "
                                      "{} (a web page of another name is not the studio's)",
                                      quoted(req.get_header_value("Host")), hosts_.front())};
  const bool safe = req.method == "GET" || req.method == "HEAD";
  if (safe && !req.path.starts_with("/api")) return std::nullopt;
  if (req.has_header("Origin") && !oneOf("Origin", origins_))
    return HttpError{403, fmt::format("request refused: Origin {} is not the studio's page {} "
                                      "(another web page may not use the studio)",
                                      quoted(req.get_header_value("Origin")), origins_.front())};
  if (!token_.empty() && (req.get_header_value_count(kTokenHeader) != 1 ||
                          !sameSecret(req.get_header_value(kTokenHeader), token_)))
    return HttpError{403, fmt::format("request refused: missing or wrong {} (open the URL "
                                      "`pdesurf studio` printed, with its ?token=)",
                                      kTokenHeader)};
  if (!safe) {
    const std::string type = req.get_header_value("Content-Type");
    std::string_view media = std::string_view(type).substr(0, type.find(';'));
    while (!media.empty() && (media.back() == ' ' || media.back() == '\t')) media.remove_suffix(1);
    if (lowerCase(media) != "application/json")
      return HttpError{415, fmt::format("request refused: a {} must declare Content-Type: "
                                        "application/json (found {})",
                                        req.method, type.empty() ? "none" : quoted(type))};
  }
  return std::nullopt;
}

}  // namespace pdesurf::studio
