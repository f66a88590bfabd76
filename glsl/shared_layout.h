// Shared by C++ and GLSL: texture units, buffer bindings and the std140
// uniform blocks. Each layout is written once here; C++ checks its offsets
// with static_asserts (lib/gl/shared_layout_checks.cpp) and GLSL declares the same
// block with the same binding. Each value has its own named member; members
// fill whole 16-byte rows (a vec4, ivec4 or mat4, a vec3 and one scalar, or
// four scalars, spare ones named padN), so std140 and C++ agree with no
// hidden padding. No scalar arrays: std140 strides their elements by 16.
// Not clang-formatted: the blocks are read as GLSL too, and their members are
// laid out by hand as the std140 rows they fill (clang-format would unindent
// them as macro arguments).
// clang-format off
#ifndef HEADLIGHT_SHARED_LAYOUT_H
#define HEADLIGHT_SHARED_LAYOUT_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace headlight::gpu {
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
using mat4 = glm::mat4;
#define HL_CONST(type, name, value) inline constexpr type name = value;
#define HL_BLOCK_BEGIN(Name, binding) \
  struct Name {                        \
    static constexpr int kBinding = binding;
#define HL_BLOCK_END(instance) \
  }                            \
  ;
#define HL_STORAGE_BEGIN(Name, binding) HL_BLOCK_BEGIN(Name, binding)
#define HL_STORAGE_END(instance) HL_BLOCK_END(instance)
#else
#define HL_CONST(type, name, value) const type name = value;
#define HL_BLOCK_BEGIN(Name, b) layout(std140, binding = b) uniform Name {
#define HL_BLOCK_END(instance) } instance;
#define HL_STORAGE_BEGIN(Name, b) layout(std430, binding = b) readonly buffer Name {
#define HL_STORAGE_END(instance) } instance;
#endif

// Texture units. Each pass binds only the units it reads.
HL_CONST(int, kUnitGbufferPosition, 0)
HL_CONST(int, kUnitGbufferNormal, 1)
HL_CONST(int, kUnitGbufferAlbedo, 2)
HL_CONST(int, kUnitGbufferMaterial, 3)
HL_CONST(int, kUnitGbufferEmissive, 4)
HL_CONST(int, kUnitSsgiNoise, 5)
HL_CONST(int, kUnitSsgi, 6)
HL_CONST(int, kUnitBrdfLut, 7)
HL_CONST(int, kUnitSkyPrefiltered, 8)
HL_CONST(int, kUnitSkyIrradiance, 9)
HL_CONST(int, kUnitShadowMaps2D, 10)
HL_CONST(int, kUnitShadowMapsCube, 11)
HL_CONST(int, kUnitBaseColorTexture, 12)
HL_CONST(int, kUnitMetallicRoughnessTexture, 13)
HL_CONST(int, kUnitNormalTexture, 14)
HL_CONST(int, kUnitOcclusionTexture, 15)
HL_CONST(int, kUnitEmissiveTexture, 16)
HL_CONST(int, kUnitDirect, 17)
HL_CONST(int, kUnitDirectDiffuse, 18)
HL_CONST(int, kUnitGbufferDepth, 19)
HL_CONST(int, kUnitSsgiSky, 20)

// The SSGI kernel never has more samples than this (the seed's count).
HL_CONST(int, kMaxKernelSamples, 64)
// Rows of the prefiltered sky table: roughness 0, 1/7, ..., 1.
HL_CONST(int, kSkyRoughnessLevels, 8)
// The split-sum BRDF table is kBrdfLutSize^2 over (N.V, roughness); the sky
// tables are kSkyTableWidth texels over direction.y in -1..1. Both are
// smooth: 64 texels resolve them within half precision.
HL_CONST(int, kBrdfLutSize, 64)
HL_CONST(int, kSkyTableWidth, 64)

// Light types as stored in GpuLight::type.
HL_CONST(int, kLightDirectional, 0)
HL_CONST(int, kLightPoint, 1)
HL_CONST(int, kLightSpot, 2)

// Per view: everything a pass needs to go between spaces.
HL_BLOCK_BEGIN(FrameBlock, 0)
  mat4 view;                // world -> view (camera looks down -Z)
  mat4 projection;          // view -> clip
  mat4 viewProjection;      // world -> clip
  vec4 cameraPosition;      // xyz world; w = 1 for orthographic, 0 for perspective
  vec4 viewport;            // width, height, 1/width, 1/height (pixels)
  vec4 nearFar;             // near, far (view-space distances), 0, 0
HL_BLOCK_END(frame)

// Per draw in the G-buffer and shadow passes.
HL_BLOCK_BEGIN(ObjectBlock, 1)
  mat4 worldFromLocal;
  mat4 normalFromLocal;     // inverse transpose of worldFromLocal (upper 3x3 used)
HL_BLOCK_END(object)

// Per material in the G-buffer pass.
HL_BLOCK_BEGIN(MaterialBlock, 2)
  vec4 baseColorFactor;     // linear RGBA
  vec4 emissiveFactor;      // linear RGB, w unused
  vec4 factors;             // metallic, roughness, normalScale, occlusionStrength
HL_BLOCK_END(material)

// SSGI settings and kernel (lib/passes/ssgi.hpp documents the ranges).
HL_BLOCK_BEGIN(SsgiBlock, 3)
  vec4 kernel[kMaxKernelSamples];  // tangent space, z >= 0, |k| <= 1
  float radiusWorld;        // kernel radius, world units (> 0)
  float biasWorld;          // depth a sample must be behind a surface to count as occluded, world units
  float intensity;          // AO strength: AO = 1 - intensity * mean occlusion
  float indirectStrength;   // scale of the indirect term
  int sampleCount;          // kernel samples used, 1..kMaxKernelSamples
  int downsample;           // resolution divisor of the SSGI target: 1, 2 or 4
  int pad0;
  int pad1;
HL_BLOCK_END(ssgi)

// The `bitmask` SSGI method (lib/passes/ssgi_bitmask.hpp documents the ranges).
HL_BLOCK_BEGIN(SsgiBitmaskBlock, 8)
  float radiusWorld;        // R: occluders count within this distance of the shaded point, world units (> 0)
  float thicknessWorld;     // each depth-buffer sample is taken as this deep behind its visible surface, world units
  float intensity;          // AO = 1 - intensity * (1 - visible fraction)
  float indirectStrength;   // scale of the indirect term
  int sliceCount;           // screen-space directions per pixel (each with its opposite)
  int stepCount;            // depth samples per direction
  int downsample;           // resolution divisor of the SSGI target: 1, 2 or 4
  int rotationIndex;        // the seed + the accumulated frame's index: rotates slice directions and step jitter
  int skyStepCount;         // long-range depth samples per direction beyond R, for the sky visibility (0: none)
  int pad0;
  int pad1;
  int pad2;
HL_BLOCK_END(bitmask)

// SSGI blur pass.
HL_BLOCK_BEGIN(SsgiBlurBlock, 7)
  float ssgiRadiusWorld;    // depth differences are judged against it
  int ssgiDownsample;       // the raw SSGI's resolution divisor (1, 2, 4)
  float pad0;
  float pad1;
HL_BLOCK_END(blur)

// Direct-light and composite passes.
HL_BLOCK_BEGIN(LightingBlock, 4)
  float skyIntensity;       // scales the sky's radiance (ambient and background)
  int lightCount;           // entries of the light buffer
  float pcfRadius;          // shadow filter radius, shadow-map texels
  float shadowNormalOffset; // how far a shadow lookup moves along the normal, in texels of the map there
  int shadowMapSize;        // texels per side of every shadow map; 0 without maps
  int pad0;
  int pad1;
  int pad2;
HL_BLOCK_END(lighting)

// Shadow pass: one light view per draw batch.
HL_BLOCK_BEGIN(ShadowBlock, 5)
  mat4 lightViewProjection;
  vec4 lightPositionFar;    // point lights: world position and far distance; w = 0 otherwise
HL_BLOCK_END(shadowView)

// The procedural sky, for the passes that tabulate it once per scene.
HL_BLOCK_BEGIN(SkyBlock, 6)
  vec4 zenith;              // linear radiance straight up (rgb), w unused
  vec4 horizon;             // at the horizon
  vec4 ground;              // below the horizon
HL_BLOCK_END(sky)

// One light, in the lights storage buffer (std430, same layout as std140 here).
struct GpuLight {
  vec3 position;            // world (point and spot)
  float range;              // 0 = infinite
  vec3 direction;           // world, unit: the way the light travels (directional and spot)
  int type;                 // kLightDirectional, kLightPoint or kLightSpot
  vec3 radiance;            // color * intensity
  int castsShadows;         // 1 if the light has a shadow map (shadowLayer >= 0), else 0
  float cosOuterCone;       // spot: cos(outer cone angle)
  float cosInnerCone;       // spot: cos(inner cone angle)
  int shadowLayer;          // layer of the planar map array, or cube of the cube array; -1 = none
  float shadowFar;          // point: the distance the cube map's depth is divided by
  float shadowTexelSize;    // directional: a texel's world size; spot: its world size per unit distance
  float pad0;
  float pad1;
  float pad2;
  mat4 shadowViewProjection;  // world -> light clip (directional and spot)
};
#ifdef __cplusplus
HL_STORAGE_BEGIN(LightBuffer, 0)
  // The C++ side uploads a std::vector<GpuLight>; this struct only names the binding.
HL_STORAGE_END(lights)
#else
HL_STORAGE_BEGIN(LightBuffer, 0)
  GpuLight lightList[];
HL_STORAGE_END(lights)
#endif

#ifdef __cplusplus
}  // namespace headlight::gpu
#endif

#endif  // HEADLIGHT_SHARED_LAYOUT_H
