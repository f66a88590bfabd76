// Point lights store linear distance / far, which the direct-light pass compares
// directly; directional and spot lights keep the rasterised depth. ALPHA_MASK
// variants cut out what gbuffer.frag cuts out, so masked holes pass light.
#include "shared_layout.h"

layout(location = 0) in vec3 vWorldPosition;
#ifdef ALPHA_MASK
#ifdef HAS_BASE_COLOR_TEXTURE
layout(location = 1) in vec2 vTexcoord;
layout(binding = kUnitBaseColorTexture) uniform sampler2D baseColorTexture;
#endif
#ifdef HAS_VERTEX_COLORS
layout(location = 2) in float vColorAlpha;
#endif
#endif

void main() {
#ifdef ALPHA_MASK
  float alpha = material.baseColorFactor.a;
#ifdef HAS_BASE_COLOR_TEXTURE
  alpha *= texture(baseColorTexture, vTexcoord).a;
#endif
#ifdef HAS_VERTEX_COLORS
  alpha *= vColorAlpha;
#endif
  if (alpha < material.alphaCutoff) discard;
#endif
  const float far = shadowView.lightPositionFar.w;
  gl_FragDepth = far > 0.0 ? length(vWorldPosition - shadowView.lightPositionFar.xyz) / far : gl_FragCoord.z;
}
