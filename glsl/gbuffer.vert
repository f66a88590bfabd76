// G-buffer vertex stage: to world space for the position and normal targets,
// to clip space for rasterisation. Attribute locations are shared_layout.h's
// kAttribute*; every instance of a primitive is one instanced draw.
#include "shared_layout.h"

layout(location = kAttributePosition) in vec3 inPosition;
layout(location = kAttributeNormal) in vec3 inNormal;
layout(location = kAttributeObjectIndex) in uint inObjectIndex;
#ifdef HAS_TEXCOORDS
layout(location = kAttributeTexcoord) in vec2 inTexcoord;
layout(location = 2) out vec2 vTexcoord;
#endif
#ifdef HAS_TANGENTS
layout(location = kAttributeTangent) in vec4 inTangent;
layout(location = 3) out vec4 vWorldTangent;
#endif

#ifdef HAS_VERTEX_COLORS
layout(location = kAttributeColor) in vec4 inColor;
layout(location = 4) out vec4 vColor;
#endif
#ifdef HAS_TEXCOORDS_1
layout(location = kAttributeTexcoord1) in vec2 inTexcoord1;
layout(location = 5) out vec2 vTexcoord1;
#endif

layout(location = 0) out vec3 vWorldPosition;
layout(location = 1) out vec3 vWorldNormal;
#ifdef TRANSMISSION_FORWARD
// KHR_materials_volume's thickness is in mesh units: the instance's scale per axis.
layout(location = 6) flat out vec3 vModelScale;
#endif
#ifdef HAS_IDS_TARGET
layout(location = 7) flat out uint vObjectIndex;  // whose ids the fragment writes
#endif
// The transmission pass redraws surfaces depth-equal with another variant of
// this shader: every variant must rasterise the same depths.
invariant gl_Position;

void main() {
  const GpuObject object = objects.objectList[inObjectIndex];
  const vec4 world = object.worldFromLocal * vec4(inPosition, 1.0);
  vWorldPosition = world.xyz;
  vWorldNormal = mat3(object.normalFromLocal) * inNormal;
#ifdef HAS_TEXCOORDS
  vTexcoord = inTexcoord;
#endif
#ifdef HAS_VERTEX_COLORS
  vColor = inColor;
#endif
#ifdef HAS_TEXCOORDS_1
  vTexcoord1 = inTexcoord1;
#endif
#ifdef HAS_TANGENTS
  vWorldTangent = vec4(mat3(object.worldFromLocal) * inTangent.xyz, inTangent.w);
#endif
#ifdef TRANSMISSION_FORWARD
  vModelScale = vec3(length(object.worldFromLocal[0].xyz), length(object.worldFromLocal[1].xyz),
                     length(object.worldFromLocal[2].xyz));
#endif
#ifdef HAS_IDS_TARGET
  vObjectIndex = inObjectIndex;
#endif
  gl_Position = frame.viewProjection * world;
}
