#include "qv/core/Result.h"

namespace qv {

Error fail(std::string message) {
  return Error{std::move(message)};
}

}  // namespace qv
