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

}  // namespace qv
