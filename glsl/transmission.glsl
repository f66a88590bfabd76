// The transmission pass's shading (lib/passes/transmission.hpp).
// gbuffer.frag built with TRANSMISSION_FORWARD evaluates a
// KHR_materials_transmission material exactly as for the G-buffer, then
// calls shadeTransmissive() instead of writing the G-buffer: the surface's
// whole radiance with every lobe it has (the direct pass's lights and
// shadows, the composite's ambient, both with the diffuse lobe's
// transmitted share replaced by the BTDF, plus the opaque image behind it
// through lobe_transmission.glsl, under the coat where it has one),
// written over lit where the surface is the nearest (depth-equal). The
// surface is in no screen-space buffer when SSGI runs, so it gets no SSGI:
// sky visibility 1, no indirect light (as a blended surface).
#ifdef TRANSMISSION_FORWARD
#include "sampling.glsl"
#include "brdf.glsl"
#include "shadows.glsl"
#include "surface.glsl"
#include "ambient.glsl"
#include "lobe_transmission.glsl"
#ifdef HAS_CLEARCOAT_LOBE
#include "lobe_clearcoat_ambient.glsl"
#endif

#ifdef HAS_TRANSMISSION_TEXTURE
layout(binding = kUnitTransmissionTexture) uniform sampler2D transmissionTexture;
#endif
#ifdef HAS_THICKNESS_TEXTURE
layout(binding = kUnitThicknessTexture) uniform sampler2D thicknessTexture;
#endif
#ifdef TRANSMISSION_TEXCOORD_1
#define TRANSMISSION_SET true
#else
#define TRANSMISSION_SET false
#endif
#ifdef THICKNESS_TEXCOORD_1
#define THICKNESS_SET true
#else
#define THICKNESS_SET false
#endif

// KHR_materials_transmission's share: transmissionFactor x texture R.
float transmissionAt() {
  float transmission = material.transmissionFactors.x;
#ifdef HAS_TRANSMISSION_TEXTURE
  transmission *= texture(transmissionTexture, textureUv(TRANSMISSION_SET, material.transmissionTransformU,
                                                         material.transmissionTransformV)).r;
#endif
  return transmission;
}

// KHR_materials_volume's thickness (mesh units; 0 = thin-walled): thicknessFactor x texture G.
float thicknessAt() {
  float thickness = material.transmissionFactors.y;
#ifdef HAS_THICKNESS_TEXTURE
  thickness *= texture(thicknessTexture, textureUv(THICKNESS_SET, material.thicknessTransformU,
                                                   material.thicknessTransformV)).g;
#endif
  return thickness;
}

// The opaque lit image with its mip chain (TransmissionPass copies it).
layout(binding = kUnitTransmissionBackground) uniform sampler2D transmissionBackground;
// Where each of its pixels lies (world; a = 0: nothing, the sky).
layout(binding = kUnitTransmissionBackgroundPosition) uniform sampler2D transmissionBackgroundPosition;
// The instance's scale per axis (gbuffer.vert): thickness is in mesh units.
layout(location = 6) flat in vec3 vModelScale;

// Replaces lit (no blending); the transmission target says how much of the
// image behind came through, and over what path length.
layout(location = 0) out vec4 outLit;
layout(location = 1) out vec4 outTransmission;

// The opaque image where the path through the volume leaves it, seen from
// the eye; a thin wall's own pixel. Clamped at the image's edges: what
// lies off-screen is not in the copy. Blurred by `blur` (the transmission
// roughness) as wide as its lobe spreads over the distance to what lies
// there (transmissionLod); the sky, at no distance, by its angle alone.
vec3 refractedBackground(vec3 exitPoint, bool thin, float blur) {
  vec2 uv = gl_FragCoord.xy * frame.viewport.zw;
  const vec4 clip = frame.viewProjection * vec4(exitPoint, 1.0);
  if (!thin && clip.w > 0.0) uv = clip.xy / clip.w * 0.5 + 0.5;
  const ivec2 size = textureSize(transmissionBackgroundPosition, 0);
  const vec4 behind = texelFetch(transmissionBackgroundPosition, clamp(ivec2(uv * vec2(size)), ivec2(0), size - 1), 0);
  // Pixels a world unit: at unit view distance (perspective), or anywhere (orthographic).
  const float pixelsPerUnit = 0.5 * frame.viewport.y * frame.projection[1][1];
  const bool orthographic = frame.cameraPosition.w > 0.5;
  float lod;
  if (behind.a == 0.0)  // the sky: its footprint in pixels is the lobe's angle's (d / z = 1); unbounded orthographic
    lod = orthographic ? 1e4 * blur : transmissionLod(blur, 1.0, pixelsPerUnit);
  else {
    const float viewDistance = max(-(frame.view * vec4(behind.xyz, 1.0)).z, 1e-6);
    lod = transmissionLod(blur, length(behind.xyz - exitPoint),
                          orthographic ? pixelsPerUnit : pixelsPerUnit / viewDistance);
  }
  return textureLod(transmissionBackground, uv, lod).rgb;
}

void shadeTransmissive(vec3 position, vec3 normal, vec3 baseColor, float metallic, float roughness, float occlusion,
                       vec3 emission, float transmission, float thickness) {
  Surface surface = makeSurface(baseColor, clamp(metallic, 0.0, 1.0), clamp(roughness, 0.0, 1.0), normal,
                                viewDirection(position));
  // KHR_materials_ior sets the dielectric's reflectance: ((ior - 1) / (ior + 1))^2, 0.04 at glTF's 1.5
  // (the specular lobe, where the scene has one, applies the same with its colour and weight).
  const float ior = material.transmissionFactors.z;
  const float iorF0 = (ior - 1.0) / (ior + 1.0);
  surface.f0 = mix(vec3(iorF0 * iorF0), surface.albedo, surface.metallic);
  surface.transmission = clamp(transmission, 0.0, 1.0);
  // Every lobe the material has, as on an opaque surface; the coat over all the surface sends.
  applyMaterialLobes(surface, normal);
#ifdef HAS_CLEARCOAT_LOBE
  const Clearcoat coat = makeClearcoat(forwardClearcoatLobe, surface.view);
  vec3 radiance = clearcoatLayer(coat, emission, vec3(0.0));
#else
  vec3 radiance = emission;
#endif
  const float blur = transmissionRoughness(clamp(roughness, 0.0, 1.0), ior);
  const int lightCount = lighting.lightCount;
  for (int i = 0; i < lightCount; ++i) {
    const GpuLight light = lights.lightList[i];
    vec3 toLight;
    const float attenuation = lightAttenuation(light, position, toLight);
    if (attenuation <= 0.0) continue;
    // A light behind the surface is seen through it: its shadow is looked
    // up on that side.
    const vec3 facing = dot(surface.normal, toLight) < 0.0 ? -surface.normal : surface.normal;
    const vec3 visibility = shadowVisibility(light, position, facing, toLight);
    vec3 brdf = transmissiveCookTorrance(surface, toLight, blur);
#ifdef HAS_CLEARCOAT_LOBE
    brdf = clearcoatLayer(coat, brdf, vec3(clearcoatSpecular(coat, surface.view, toLight)));
#endif
    radiance += brdf * light.radiance * (attenuation * visibility);
  }
#ifdef HAS_SKY
  // The composite's ambient term; its diffuse part keeps the share not transmitted.
  const float materialOcclusion = clamp(occlusion, 0.0, 1.0);
#ifdef HAS_CLEARCOAT_LOBE
  radiance += clearcoatLayer(coat, ambientLight(surface, materialOcclusion, 1.0, vec3(0.0)),
                             clearcoatAmbient(coat, surface.view, materialOcclusion, 1.0));
#else
  radiance += ambientLight(surface, materialOcclusion, 1.0, vec3(0.0));
#endif
#endif
  const float pathThickness = max(thickness, 0.0);
  // The length of the unit-thickness ray times the thickness, not length(path):
  // its squares overflow float from a path of ~1.8e19 (thicknessFactor is unbounded).
  const vec3 unitPath = volumeTransmissionRay(surface.normal, surface.view, 1.0, ior, vModelScale);
  const vec3 path = unitPath * pathThickness;
  const float pathLength = length(unitPath) * pathThickness;
  const vec3 attenuation =
      volumeAttenuation(pathLength, material.attenuationColor.rgb, material.transmissionFactors.w);
  vec3 throughput = transmissionThroughput(surface, specularAlbedoOf(surface), attenuation);
#ifdef HAS_CLEARCOAT_LOBE
  throughput = clearcoatLayer(coat, throughput, vec3(0.0));  // what the coat does not reflect goes on through
#endif
  radiance += throughput * refractedBackground(position + path, pathThickness == 0.0, blur);
  outLit = vec4(radiance, 1.0);
  outTransmission = vec4(throughput, pathLength);
}
#endif
