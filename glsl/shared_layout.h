// Shared by C++ and GLSL: texture units, buffer bindings and the std140
// uniform blocks. Each layout is written once here and GLSL declares the same
// block with the same binding; the GL layout test proves every offset from
// the block's size (why: lib/gl/shared_layout_checks.cpp), so a new member
// needs no check of its own. Each value has its own named member; members
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
using uvec4 = glm::uvec4;
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

// ---- The one list of units and bindings ----------------------------------------
// Every texture unit, image unit, uniform-block binding and storage-block
// binding is a row of one of these lists, and nowhere else: GLSL and C++ both
// declare their constants from the rows, the distinctness checks
// (lib/gl/shared_layout_checks.cpp) and the GL layout test
// (tests/layout_gl_tests.cpp) walk them, so a new unit or block cannot be
// left out of either. A block names its binding constant in HL_BLOCK_BEGIN:
// a block without a row does not compile.

// Texture units (X(name, unit)). Each pass binds only the units it reads.
#define HL_TEXTURE_UNITS(X)                 \
  X(kUnitGbufferPosition, 0)              \
  X(kUnitGbufferNormal, 1)                \
  X(kUnitGbufferAlbedo, 2)                \
  X(kUnitGbufferMaterial, 3)              \
  X(kUnitGbufferEmissive, 4)              \
  X(kUnitSsgiNoise, 5)                    \
  X(kUnitSsgi, 6)                         \
  X(kUnitBrdfLut, 7)                      \
  X(kUnitSkyPrefiltered, 8)               \
  X(kUnitSkyIrradiance, 9)                \
  X(kUnitShadowMaps2D, 10)                \
  X(kUnitShadowMapsCube, 11)              \
  X(kUnitBaseColorTexture, 12)            \
  X(kUnitMetallicRoughnessTexture, 13)    \
  X(kUnitNormalTexture, 14)               \
  X(kUnitOcclusionTexture, 15)            \
  X(kUnitEmissiveTexture, 16)             \
  X(kUnitDirect, 17)                      \
  X(kUnitDirectDiffuse, 18)               \
  X(kUnitGbufferDepth, 19)                \
  X(kUnitSsgiSky, 20)                     \
  X(kUnitEnvironmentSpecular, 21)         \
  X(kUnitEnvironmentIrradiance, 22)       \
  X(kUnitEnvironmentBackground, 23)       \
  X(kUnitSpecularLobe, 24)                \
  X(kUnitClearcoatLobe, 25)               \
  X(kUnitSheenLobe, 26)                   \
  X(kUnitAnisotropyLobe, 27)              \
  X(kUnitIridescenceLobe, 28)             \
  X(kUnitSpecularTexture, 29)             \
  X(kUnitSpecularColorTexture, 30)        \
  X(kUnitClearcoatTexture, 31)            \
  X(kUnitClearcoatRoughnessTexture, 32)   \
  X(kUnitClearcoatNormalTexture, 33)      \
  X(kUnitSheenColorTexture, 34)           \
  X(kUnitSheenRoughnessTexture, 35)       \
  X(kUnitIridescenceTexture, 36)          \
  X(kUnitIridescenceThicknessTexture, 37) \
  X(kUnitAnisotropyTexture, 38)           \
  X(kUnitTransmissionTexture, 39)         \
  X(kUnitThicknessTexture, 40)            \
  X(kUnitTransmissionBackground, 41)      \
  X(kUnitSsgiSpecular, 42)                \
  X(kUnitPassAccumulated0, 43)            \
  X(kUnitPassAccumulated1, 44)            \
  X(kUnitPassAccumulated2, 45)            \
  X(kUnitPassAccumulated3, 46)            \
  X(kUnitSsgiSurface, 47)                 \
  X(kUnitLit, 48)                         \
  X(kUnitShadowTransmittance2D, 49)       \
  X(kUnitShadowTransmittanceCube, 50)     \
  X(kUnitTransmissionBackgroundPosition, 51)

// Image units (X(name, unit)), for image load/store: a fullscreen pass's
// compute form writes its outputs 0..3 to these (glsl/fullscreen_entry.comp).
#define HL_IMAGE_UNITS(X)    \
  X(kImagePassOutput0, 0)    \
  X(kImagePassOutput1, 1)    \
  X(kImagePassOutput2, 2)    \
  X(kImagePassOutput3, 3)

// Uniform blocks (X(block, binding name, binding)): std140, below.
#define HL_UNIFORM_BLOCKS(X)                \
  X(FrameBlock, kBindingFrame, 0)           \
  X(MaterialBlock, kBindingMaterial, 2)     \
  X(SsgiBlock, kBindingSsgi, 3)             \
  X(LightingBlock, kBindingLighting, 4)     \
  X(ShadowBlock, kBindingShadow, 5)         \
  X(SkyBlock, kBindingSky, 6)               \
  X(SsgiBlurBlock, kBindingSsgiBlur, 7)     \
  X(SsgiBitmaskBlock, kBindingSsgiBitmask, 8)

// Block members that carry a render setting unchanged (X(block, member,
// setting row), the row's '-' written as is): filled from the settings table
// by fillSettingFields (lib/settings/setting_fields.hpp), so such a setting
// needs no line in its pass. C++ only; GLSL never expands it.
#define HL_SETTING_FIELDS(X)                                \
  X(SsgiBlock, radiusWorld, ssgi-radius)                    \
  X(SsgiBlock, biasWorld, ssgi-bias)                        \
  X(SsgiBlock, intensity, ssgi-intensity)                   \
  X(SsgiBlock, indirectStrength, ssgi-indirect)             \
  X(SsgiBitmaskBlock, radiusWorld, ssgi-radius)             \
  X(SsgiBitmaskBlock, thicknessWorld, ssgi-thickness)       \
  X(SsgiBitmaskBlock, intensity, ssgi-intensity)            \
  X(SsgiBitmaskBlock, indirectStrength, ssgi-indirect)      \
  X(SsgiBitmaskBlock, sliceCount, ssgi-slices)              \
  X(SsgiBitmaskBlock, stepCount, ssgi-steps)                \
  X(SsgiBitmaskBlock, skyStepCount, ssgi-sky-steps)

// Storage blocks (X(block, binding name, binding)): std430, below.
#define HL_STORAGE_BLOCKS(X)                \
  X(LightBuffer, kBindingLights, 0)         \
  X(ObjectBuffer, kBindingObjects, 1)       \
  X(VirtualLightBuffer, kBindingVirtualLights, 2) \
  X(LightFieldBuffer, kBindingLightField, 3)

#define HL_UNIT_CONST(name, unit) HL_CONST(int, name, unit)
#define HL_BINDING_CONST(block, name, binding) HL_CONST(int, name, binding)
HL_TEXTURE_UNITS(HL_UNIT_CONST)
HL_IMAGE_UNITS(HL_UNIT_CONST)
HL_UNIFORM_BLOCKS(HL_BINDING_CONST)
HL_STORAGE_BLOCKS(HL_BINDING_CONST)

// A fullscreen pass's entries (glsl/fullscreen_entry.frag, .comp): the
// accumulated frames' weight is the default block's uniform at this
// location (set with glProgramUniform1f, never looked up by name), and the
// compute form's work groups are this many pixels square (64 invocations:
// two warps or one wavefront).
HL_CONST(int, kLocationAccumulateWeight, 0)
HL_CONST(int, kPassGroupSize, 8)

// The SSGI kernel never has more samples than this (the seed's count).
HL_CONST(int, kMaxKernelSamples, 64)
// Rows of the prefiltered sky table: roughness 0, 1/7, ..., 1.
HL_CONST(int, kSkyRoughnessLevels, 8)
// The split-sum BRDF table is kBrdfLutSize^2 over (N.V, roughness); the sky
// tables are kSkyTableWidth texels over direction.y in -1..1. Both are
// smooth: 64 texels resolve them within half precision.
HL_CONST(int, kBrdfLutSize, 64)
HL_CONST(int, kSkyTableWidth, 64)

// KHR_materials_iridescence: films thicker than this (nm) are drawn at it.
// At 10 um the thin-film Fresnel's Fourier terms are below exp(-100) of
// their amplitude, so only the incoherent sum is left either way; it also
// keeps the lobe's half-float attachment (max 65504) finite.
HL_CONST(float, kMaxFilmThicknessNm, 10000.0f)
// And its IORs (the film's and the base's) above this are drawn at it: a
// surface of IOR 1e4 already reflects 0.9996 at normal incidence, and the
// bound keeps (n - 1) / (n + 1) and the half-float attachment finite for the
// largest IOR a file may give (any finite number >= 1).
HL_CONST(float, kMaxIridescenceIor, 10000.0f)

// Light types as stored in GpuLight::type.
HL_CONST(int, kLightDirectional, 0)
HL_CONST(int, kLightPoint, 1)
HL_CONST(int, kLightSpot, 2)

// View-space z (negative in front of the camera) of a depth-buffer value
// as NDC depth, ndc = 2 d - 1 (d in GL's default 0..1 range), for
// perspective and orthographic projections alike:
// (k.x + k.y ndc) / (k.z + k.w ndc). The coefficients k are computed once on
// the CPU (viewZCoefficients, lib/gl/readback.hpp) and passed in
// FrameBlock; the depth target's readback uses the same formula.
#define HL_VIEW_Z_FROM_NDC_DEPTH(ndc, k) (((k).x + (k).y * (ndc)) / ((k).z + (k).w * (ndc)))

// Per view: everything a pass needs to go between spaces.
HL_BLOCK_BEGIN(FrameBlock, kBindingFrame)
  mat4 view;                // world -> view (camera looks down -Z)
  mat4 projection;          // view -> clip
  mat4 viewProjection;      // world -> clip
  vec4 cameraPosition;      // xyz world; w = 1 for orthographic, 0 for perspective
  vec4 viewport;            // width, height, 1/width, 1/height (pixels)
  vec4 depthToViewZ;        // k: view-space z of NDC depth is HL_VIEW_Z_FROM_NDC_DEPTH(ndc, k) (viewZCoefficients)
HL_BLOCK_END(frame)


// Per material in the G-buffer pass.
HL_BLOCK_BEGIN(MaterialBlock, kBindingMaterial)
  vec4 baseColorFactor;     // linear RGBA
  vec4 emissiveFactor;      // linear RGB, w unused
  vec4 factors;             // metallic, roughness, normalScale, occlusionStrength
  float alphaCutoff;        // alphaMode MASK (ALPHA_MASK variants): alpha below it is cut out
  float pad0;
  float pad1;
  float pad2;
  // KHR_texture_transform per texture (read only by HAS_TEXTURE_TRANSFORM
  // variants): the affine 2x3 matrix's rows, u' = dot(xyz, (u, v, 1)) and
  // v' likewise; w unused. Identity rows for untransformed textures.
  vec4 baseColorTransformU;
  vec4 baseColorTransformV;
  vec4 metallicRoughnessTransformU;
  vec4 metallicRoughnessTransformV;
  vec4 normalTransformU;
  vec4 normalTransformV;
  vec4 occlusionTransformU;
  vec4 occlusionTransformV;
  vec4 emissiveTransformU;
  vec4 emissiveTransformV;
  // KHR_materials_* factors (lib/include/headlight/scene.hpp), the
  // specification's defaults where the material lacks the extension; each
  // read only by the variants of its lobe or pass.
  vec4 specularFactors;      // specularColorFactor.rgb, specularFactor
  vec4 clearcoatFactors;     // clearcoatFactor, clearcoatRoughnessFactor, clearcoatNormalScale, unused
  vec4 sheenFactors;         // sheenColorFactor.rgb, sheenRoughnessFactor
  vec4 iridescenceFactors;   // iridescenceFactor, iridescenceIor, thickness minimum, maximum (nm)
  vec4 anisotropyFactors;    // anisotropyStrength, cos and sin of anisotropyRotation, unused
  vec4 transmissionFactors;  // transmissionFactor, thicknessFactor, ior, attenuationDistance (0: none)
  vec4 attenuationColor;     // KHR_materials_volume's, w unused
  // The extensions' textures' KHR_texture_transform rows, as above.
  vec4 specularTransformU;
  vec4 specularTransformV;
  vec4 specularColorTransformU;
  vec4 specularColorTransformV;
  vec4 clearcoatTransformU;
  vec4 clearcoatTransformV;
  vec4 clearcoatRoughnessTransformU;
  vec4 clearcoatRoughnessTransformV;
  vec4 clearcoatNormalTransformU;
  vec4 clearcoatNormalTransformV;
  vec4 sheenColorTransformU;
  vec4 sheenColorTransformV;
  vec4 sheenRoughnessTransformU;
  vec4 sheenRoughnessTransformV;
  vec4 iridescenceTransformU;
  vec4 iridescenceTransformV;
  vec4 iridescenceThicknessTransformU;
  vec4 iridescenceThicknessTransformV;
  vec4 anisotropyTransformU;
  vec4 anisotropyTransformV;
  vec4 transmissionTransformU;
  vec4 transmissionTransformV;
  vec4 thicknessTransformU;
  vec4 thicknessTransformV;
HL_BLOCK_END(material)

// SSGI settings and kernel (lib/passes/ssgi.hpp documents the ranges).
HL_BLOCK_BEGIN(SsgiBlock, kBindingSsgi)
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
HL_BLOCK_BEGIN(SsgiBitmaskBlock, kBindingSsgiBitmask)
  float radiusWorld;        // R: occluders count within this distance of the shaded point, world units (> 0)
  float thicknessWorld;     // each depth-buffer sample is taken as this deep behind its visible surface, world units
  float intensity;          // AO = 1 - intensity * (1 - visible fraction)
  float indirectStrength;   // scale of the indirect term
  int sliceCount;           // screen-space directions per pixel (each with its opposite)
  int stepCount;            // depth samples per direction
  int downsample;           // resolution divisor of the SSGI target: 1, 2 or 4
  int rotationIndex;        // the seed + the accumulated frame's index: rotates slice directions and step jitter
  int skyStepCount;         // long-range depth samples per direction beyond R, for the sky visibility (0: none)
  int part;                 // kBitmaskBoth, kBitmaskNearField or kBitmaskFarField: what the draw writes
  int virtualLightCount;    // entries of the virtual light buffer the far field gathers (0: none)
  int farLightSource;       // what the marches beyond R gather: kFarLightDirect, kFarLightEmission or kFarLightNone
  // The light field (lib/passes/light_field.hpp) the far field reads: probe (0, 0, 0)'s position and the
  // spacing between probes, world (w unused); probes per axis (all 0: no field), w unused.
  vec4 lightFieldOrigin;
  vec4 lightFieldSpacing;
  ivec4 lightFieldCounts;
HL_BLOCK_END(bitmask)

// SsgiBitmaskBlock::farLightSource. Without virtual lights the marches
// beyond R gather the direct pass's Lambertian target (direct light and
// emission); with them the virtual lights carry the direct light, and the
// marches gather emission only (the G-buffer's emissive target), or
// nothing in a scene without emission.
HL_CONST(int, kFarLightDirect, 0)
HL_CONST(int, kFarLightEmission, 1)
HL_CONST(int, kFarLightNone, 2)
// How many interleaved subsets the virtual lights are split into: each
// pixel of a 4x4 tile gathers one (the far field's blur averages them).
HL_CONST(int, kVirtualLightSubsets, 16)

// SsgiBitmaskBlock::part. Both: location 0 the near field (AO and light
// within R), location 1 the far field (sky visibility and light from beyond
// R). NearField: location 0 only (the block's skyStepCount is 0). FarField:
// the far field, to location 0, its sky visibility divided by the AO within
// R (the blur multiplies it back by the full-resolution AO).
HL_CONST(int, kBitmaskBoth, 0)
HL_CONST(int, kBitmaskNearField, 1)
HL_CONST(int, kBitmaskFarField, 2)

// SSGI blur pass.
HL_BLOCK_BEGIN(SsgiBlurBlock, kBindingSsgiBlur)
  float ssgiRadiusWorld;    // depth differences are judged against it
  int ssgiDownsample;       // the raw SSGI's resolution divisor (1, 2, 4)
  int skyDownsample;        // the raw sky's: ssgiDownsample, or the far field's own pass's (2, 4)
  int outputDownsample;     // the output's: 1, or the far field's when skyOnly
  int skyTapRadius;         // the sky's window: 3 (7x7, sigma 2 texels), 1 (3x3, an upsample of a blurred sky), or
                            // the far field's own blur's line
  int skyOnly;              // 1: only the sky is filtered, and written to location 0 (the far field's own blur)
  int skyAxisX;             // skyOnly: the line the window runs along, (1, 0) or (0, 1); (0, 0) a square
  int skyAxisY;
HL_BLOCK_END(blur)

// Direct-light and composite passes.
HL_BLOCK_BEGIN(LightingBlock, kBindingLighting)
  float skyIntensity;       // scales the sky's radiance, or the environment map's (ambient and background)
  int lightCount;           // entries of the light buffer
  float pcfRadius;          // shadow filter radius, shadow-map texels
  float shadowNormalOffset; // how far a shadow lookup moves along the normal, in texels of the map there
  int shadowMapSize;        // texels per side of the planar shadow maps (cubes: half); 0 without maps
  float environmentRotationCos; // the environment map's turn about +Y (environment/equirect.hpp worldToMap)
  float environmentRotationSin;
  int environmentBackground;    // 1: the map shows behind the scene; 0: the background is 0
HL_BLOCK_END(lighting)

// Shadow pass: one light view per draw batch.
HL_BLOCK_BEGIN(ShadowBlock, kBindingShadow)
  mat4 lightViewProjection;
  vec4 lightPositionFar;    // point lights: world position and far distance; w = 0 otherwise
  // The transmittance maps' distances are measured from here: point and spot
  // lights' world position with w = 1; directional lights' direction of
  // travel with w = 0 (the distance along it from the world's origin).
  vec4 lightOrigin;
HL_BLOCK_END(shadowView)

// The procedural sky, for the passes that tabulate it once per scene.
HL_BLOCK_BEGIN(SkyBlock, kBindingSky)
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
HL_STORAGE_BEGIN(LightBuffer, kBindingLights)
  // The C++ side uploads a std::vector<GpuLight>; this struct only names the binding.
HL_STORAGE_END(lights)
#else
HL_STORAGE_BEGIN(LightBuffer, kBindingLights)
  GpuLight lightList[];
HL_STORAGE_END(lights)
#endif

// One instance's transforms, in the objects storage buffer (std430, same
// layout as std140 here): the G-buffer and shadow passes draw every instance
// of a primitive in one instanced draw, and each vertex finds its instance's
// entry by the instanced attribute kAttributeObjectIndex.
struct GpuObject {
  mat4 worldFromLocal;
  mat4 normalFromLocal;     // cofactor of worldFromLocal's upper 3x3 (normalMatrix; upper 3x3 used)
  uvec4 ids;                // the ids target's mesh instance, mesh, material, mesh primitive (scene/ids.hpp)
};
#ifdef __cplusplus
HL_STORAGE_BEGIN(ObjectBuffer, kBindingObjects)
  // The C++ side uploads a std::vector<GpuObject>; this struct only names the binding.
HL_STORAGE_END(objects)
#else
HL_STORAGE_BEGIN(ObjectBuffer, kBindingObjects)
  GpuObject objectList[];
HL_STORAGE_END(objects)
#endif

// One virtual point light (lib/passes/virtual_lights.hpp): a texel of a
// light's view of the scene, re-emitting the light it receives as a
// Lambertian surface. Radiant intensity toward w: flux * max(n . w, 0) / pi.
struct GpuVirtualLight {
  vec4 position;            // world; w = the index of its light in the light buffer
  vec4 normal;              // world, unit, facing the light; w = the texel's area on the surface
  vec4 flux;                // reflected flux (1 - metallic) albedo * received power, rgb; w unused
};
#ifdef __cplusplus
HL_STORAGE_BEGIN(VirtualLightBuffer, kBindingVirtualLights)
  // The C++ side uploads a std::vector<GpuVirtualLight>; this struct only names the binding.
HL_STORAGE_END(virtualLights)
#else
HL_STORAGE_BEGIN(VirtualLightBuffer, kBindingVirtualLights)
  GpuVirtualLight virtualLightList[];
HL_STORAGE_END(virtualLights)
#endif

// One probe of the light field (lib/passes/light_field.hpp), on two
// kLightFieldMapSize^2 octahedral maps (texel (u, v) at u + v * size): the
// irradiance it receives from the virtual lights for each normal (rgb), and
// the mean and mean square of the distance to what it sees about each
// direction, two texels to a vec4 (xy, zw).
HL_CONST(int, kLightFieldMapSize, 8)
struct GpuLightProbe {
  vec4 irradiance[kLightFieldMapSize * kLightFieldMapSize];  // rgb; [0].w: 1 in use, 0 inside a closed mesh
  vec4 moments[kLightFieldMapSize * kLightFieldMapSize / 2];
};
#ifdef __cplusplus
HL_STORAGE_BEGIN(LightFieldBuffer, kBindingLightField)
  // The C++ side uploads a std::vector<GpuLightProbe>; this struct only names the binding.
HL_STORAGE_END(lightField)
#else
HL_STORAGE_BEGIN(LightFieldBuffer, kBindingLightField)
  GpuLightProbe probes[];
HL_STORAGE_END(lightField)
#endif

// Vertex attribute locations of the scene's primitives (lib/gl/gpu_scene.cpp).
HL_CONST(int, kAttributePosition, 0)
HL_CONST(int, kAttributeNormal, 1)
HL_CONST(int, kAttributeTexcoord, 2)
HL_CONST(int, kAttributeTangent, 3)
HL_CONST(int, kAttributeObjectIndex, 4)  // per instance (divisor 1): the entry of ObjectBuffer
HL_CONST(int, kAttributeColor, 5)        // COLOR_0, linear RGBA (HAS_VERTEX_COLORS)
HL_CONST(int, kAttributeTexcoord1, 6)    // TEXCOORD_1 (HAS_TEXCOORDS_1)

#ifdef __cplusplus
}  // namespace headlight::gpu
#endif

#endif  // HEADLIGHT_SHARED_LAYOUT_H
