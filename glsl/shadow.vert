// Shadow pass vertex stage: world position for the distance a point light's
// cube stores, light clip space for rasterisation.
#include "shared_layout.h"

layout(location = kAttributePosition) in vec3 inPosition;
layout(location = kAttributeObjectIndex) in uint inObjectIndex;
layout(location = 0) out vec3 vWorldPosition;

void main() {
  const GpuObject object = objects.objectList[inObjectIndex];
  const vec4 world = object.worldFromLocal * vec4(inPosition, 1.0);
  vWorldPosition = world.xyz;
  gl_Position = shadowView.lightViewProjection * world;
}
