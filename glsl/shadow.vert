// Shadow pass vertex stage: world position for the distance a point light's
// cube stores, light clip space for rasterisation.
#include "shared_layout.h"

layout(location = 0) in vec3 inPosition;
layout(location = 0) out vec3 vWorldPosition;

void main() {
  const vec4 world = object.worldFromLocal * vec4(inPosition, 1.0);
  vWorldPosition = world.xyz;
  gl_Position = shadowView.lightViewProjection * world;
}
