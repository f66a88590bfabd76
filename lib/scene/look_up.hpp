#pragma once
// The up vector for a view along `direction` (glm::lookAt's third argument):
// +Y, or +X where the direction is within 8 degrees of vertical and +Y
// would leave lookAt no plane. Shared by the shadow maps' and the virtual
// lights' views of the scene.
#include <cmath>

#include <glm/glm.hpp>

namespace headlight {

inline glm::vec3 upFor(const glm::vec3& direction) {
  return std::abs(direction.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
}

}  // namespace headlight
