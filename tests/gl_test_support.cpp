#include "gl_test_support.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace headlight::test {

Primitive quad(glm::vec3 center, glm::vec3 normal, float halfSize) {
  // Two axes spanning the plane, ordered so the winding faces `normal`.
  const glm::vec3 helper = std::abs(normal.y) > 0.5f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  const glm::vec3 u = glm::normalize(glm::cross(helper, normal)) * halfSize;
  const glm::vec3 v = glm::normalize(glm::cross(normal, u)) * halfSize;
  Primitive primitive;
  primitive.positions = {center - u - v, center + u - v, center + u + v, center - u + v};
  primitive.normals.assign(4, normal);
  primitive.indices = {0, 1, 2, 0, 2, 3};
  for (const auto& p : primitive.positions) primitive.bounds.extend(p);
  return primitive;
}

Camera lookAtCamera(glm::vec3 eye, glm::vec3 target, float yfov, float orthoHalfHeight) {
  Camera camera;
  camera.worldFromCamera = glm::inverse(glm::lookAt(eye, target, glm::vec3(0, 1, 0)));
  camera.yfov = yfov;
  if (orthoHalfHeight > 0) {
    camera.projection = Camera::Projection::Orthographic;
    camera.ymag = orthoHalfHeight;
    camera.xmag = orthoHalfHeight;
  }
  return camera;
}

double meanWhere(const Frame& frame, const ImageF& image, int channel,
                 const std::function<bool(glm::vec3, glm::vec3)>& select, int& count) {
  double sum = 0;
  count = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      if (frame.position.at(x, y, 3) == 0.0f) continue;
      const glm::vec3 p(frame.position.at(x, y, 0), frame.position.at(x, y, 1), frame.position.at(x, y, 2));
      const glm::vec3 n(frame.normal.at(x, y, 0), frame.normal.at(x, y, 1), frame.normal.at(x, y, 2));
      if (!select(p, n)) continue;
      sum += image.at(x, y, channel);
      ++count;
    }
  return count > 0 ? sum / count : 0.0;
}

}  // namespace headlight::test
