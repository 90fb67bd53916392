// The one exception type of the scene readers. Every message names the file and the element
// that was refused (a line, a collision object id, a link), so that a user can fix the input
// without reading our code.
#pragma once

#include <stdexcept>
#include <string>

namespace dss {

class SceneError : public std::runtime_error {
 public:
  explicit SceneError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace dss
