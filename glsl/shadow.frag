// Point lights store linear distance / far, which the direct-light pass compares
// directly; directional and spot lights keep the rasterised depth.
#include "shared_layout.h"

layout(location = 0) in vec3 vWorldPosition;

void main() {
  const float far = shadowView.lightPositionFar.w;
  gl_FragDepth = far > 0.0 ? length(vWorldPosition - shadowView.lightPositionFar.xyz) / far : gl_FragCoord.z;
}
