#include "qv/scene/Fetcher.h"

namespace qv {

std::string resolveUrl(const std::string& base, const std::string& relative) {
  if (relative.find("://") != std::string::npos || (!relative.empty() && relative[0] == '/')) return relative;
  // Strip the query and fragment of the base, then its last path segment.
  std::string dir = base.substr(0, base.find_first_of("?#"));
  const auto slash = dir.rfind('/');
  dir = slash == std::string::npos ? std::string() : dir.substr(0, slash + 1);
  return dir + relative;
}

namespace {

std::string lowerPrefix(const std::string& url, std::size_t n) {
  std::string out = url.substr(0, n);
  for (char& c : out) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  return out;
}

}  // namespace

bool isAbsoluteHttpUrl(const std::string& url) {
  return lowerPrefix(url, 7) == "http://" || lowerPrefix(url, 8) == "https://";
}

std::string dataUrlProblem(const std::string& url) {
  if (url.empty()) return "no address given";
  if (url.size() > 4096) return "the address is longer than 4096 characters";
  for (const char c : url) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return "the address contains control characters";
  }
  if (isAbsoluteHttpUrl(url)) return {};
  // A scheme is letters, digits, '+', '-' or '.' before the first ':' that comes before any '/',
  // '?' or '#'; "//host/..." (scheme-relative) is another site too, over the page's own scheme.
  const auto colon = url.find(':');
  const auto stop = url.find_first_of("/?#");
  if (colon != std::string::npos && (stop == std::string::npos || colon < stop)) {
    return "only http:// and https:// addresses and paths on this site are allowed, not \"" + url.substr(0, colon + 1) +
           "\"";
  }
  return {};
}

std::string dataOriginProblem(const DataOriginPolicy& policy) {
  if (policy.pageOrigin.empty()) return {};
  const std::string& origin = policy.urlOrigin;
  if (origin.empty() || origin == "null") {
    return "The city's address in this link could not be resolved to a web site, so nothing was loaded.";
  }
  if (origin == policy.pageOrigin) return {};
  for (const std::string& allowed : policy.allowedOrigins) {
    if (origin == allowed) return {};
  }
  const std::string shown = origin.substr(0, 200);
  return "This link asks QuakeView to show a city from " + shown +
         ", which this site does not allow, so nothing was loaded from it. This site (" + policy.pageOrigin +
         ") shows data only from itself and from the origins listed in config.json beside its index.html. If " + shown +
         " is a source you trust, the site's administrator can allow it there: {\"dataOrigins\": [\"" + shown + "\"]}.";
}

std::string dataOriginDescription(const DataOriginPolicy& policy) {
  if (policy.pageOrigin.empty()) return {};
  if (policy.urlOrigin == policy.pageOrigin) return "this site (" + policy.pageOrigin + ")";
  return policy.urlOrigin + " (allowed by this site's config.json)";
}

}  // namespace qv
