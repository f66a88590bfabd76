// G-buffer vertex stage: to world space for the position and normal targets,
// to clip space for rasterisation. Attribute locations match
// lib/gpu_scene.cpp's.
#include "shared_layout.h"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
#ifdef HAS_TEXCOORDS
layout(location = 2) in vec2 inTexcoord;
layout(location = 2) out vec2 vTexcoord;
#endif
#ifdef HAS_TANGENTS
layout(location = 3) in vec4 inTangent;
layout(location = 3) out vec4 vWorldTangent;
#endif

layout(location = 0) out vec3 vWorldPosition;
layout(location = 1) out vec3 vWorldNormal;

void main() {
  const vec4 world = object.worldFromLocal * vec4(inPosition, 1.0);
  vWorldPosition = world.xyz;
  vWorldNormal = mat3(object.normalFromLocal) * inNormal;
#ifdef HAS_TEXCOORDS
  vTexcoord = inTexcoord;
#endif
#ifdef HAS_TANGENTS
  vWorldTangent = vec4(mat3(object.worldFromLocal) * inTangent.xyz, inTangent.w);
#endif
  gl_Position = frame.viewProjection * world;
}
