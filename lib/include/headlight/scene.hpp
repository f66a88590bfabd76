#pragma once
// The scene model: what the renderer needs from a glTF file, and nothing more.
// Geometry is stored once per distinct set of glTF accessors and drawn once
// per instance, each instance with its own material, so a file whose 98
// sphere meshes differ only in material keeps one sphere in memory.
//
// Conventions (see docs/PIPELINE.md): right-handed world space, +Y up, glTF
// units (metres unless the file says otherwise); cameras look down their -Z.
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/type_precision.hpp>
#include "headlight/export.hpp"

namespace headlight HEADLIGHT_PUBLIC {

struct Bounds {
  glm::vec3 min{std::numeric_limits<float>::infinity()};
  glm::vec3 max{-std::numeric_limits<float>::infinity()};

  bool empty() const { return min.x > max.x; }
  void extend(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void extend(const Bounds& other) {
    if (!other.empty()) {
      extend(other.min);
      extend(other.max);
    }
  }
  glm::vec3 center() const { return (min + max) * 0.5f; }
  glm::vec3 size() const { return max - min; }
  // Radius of the sphere around center() that holds the box; 0 for an empty
  // box. In double: the squared diagonal of a 1e20-unit scene overflows float.
  float radius() const { return empty() ? 0.0f : float(glm::length(glm::dvec3(size())) * 0.5); }
  // The box of this box's eight corners moved by `transform`.
  Bounds transformed(const glm::mat4& transform) const;
};

// A decoded texture image: 8-bit RGBA, rows top first, as glTF's UV origin
// (top-left) expects, so UVs need no flip when uploaded row by row.
struct ImageData {
  std::string name;
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;
};

// KHR_texture_transform on one texture reference: the UV a texture is
// sampled at is T(offset) * R(rotation) * S(scale) * (u, v, 1). In UV space
// (v down the image) the rotation turns (u, v) by -rotation, so the image
// appears turned clockwise on screen, as the extension's test model
// (TextureTransformTest) shows. Every value finite (the loader checks).
struct TextureTransform {
  glm::vec2 offset{0.0f};
  float rotation = 0.0f;  // radians
  glm::vec2 scale{1.0f};

  bool identity() const { return offset == glm::vec2(0.0f) && rotation == 0.0f && scale == glm::vec2(1.0f); }
  // The 2x3 affine matrix's rows: u' = dot(rowU, (u, v, 1)), v' = dot(rowV, (u, v, 1)).
  glm::vec3 rowU() const { return {std::cos(rotation) * scale.x, std::sin(rotation) * scale.y, offset.x}; }
  glm::vec3 rowV() const { return {-std::sin(rotation) * scale.x, std::cos(rotation) * scale.y, offset.y}; }
  glm::vec2 apply(glm::vec2 uv) const {
    const glm::vec3 p(uv, 1.0f);
    return {glm::dot(rowU(), p), glm::dot(rowV(), p)};
  }
};

// How many TEXCOORD_n sets are rendered: a texCoord of kTexcoordSets or more
// samples TEXCOORD_0 (gltf_features names it).
inline constexpr int kTexcoordSets = 2;

// glTF's sampler codes are the GL enum values, so they are kept as is.
struct TextureRef {
  int image = -1;     // index into Scene::images; -1 = no texture
  int texCoord = 0;   // the TEXCOORD_n set (KHR_texture_transform's texCoord, when given, already applied)
  TextureTransform transform;  // KHR_texture_transform; identity when absent
  int wrapS = 0x2901;      // GL_REPEAT
  int wrapT = 0x2901;      // GL_REPEAT
  int minFilter = 0x2703;  // GL_LINEAR_MIPMAP_LINEAR
  int magFilter = 0x2601;  // GL_LINEAR
  bool present() const { return image >= 0; }
};

// glTF's alphaMode. MASK cuts out where alpha < alphaCutoff (G-buffer,
// shadows and the reference); BLEND is drawn after the opaque surfaces, back
// to front over lit, casts no shadow and is not in the G-buffer
// (docs/PIPELINE.md, the blend pass).
enum class AlphaMode { Opaque, Mask, Blend };

// glTF's metallic-roughness material.
// The ratified KHR_materials_* extensions, with the specification's property
// names and defaults. A Material holds one only when its glTF material has
// the extension; a texture's channel is noted where the specification picks
// one. Loading checks the ranges (lib/gltf/material_extensions.cpp).
struct MaterialSpecular {  // KHR_materials_specular
  float specularFactor = 1.0f;              // 0..1: the dielectric specular weight
  TextureRef specularTexture;               // A
  glm::vec3 specularColorFactor{1.0f};      // >= 0: the dielectric F0 colour
  TextureRef specularColorTexture;          // RGB, sRGB
};
struct MaterialClearcoat {  // KHR_materials_clearcoat
  float clearcoatFactor = 0.0f;             // 0..1
  TextureRef clearcoatTexture;              // R
  float clearcoatRoughnessFactor = 0.0f;    // 0..1
  TextureRef clearcoatRoughnessTexture;     // G
  TextureRef clearcoatNormalTexture;        // tangent space
  float clearcoatNormalScale = 1.0f;
};
struct MaterialSheen {  // KHR_materials_sheen
  glm::vec3 sheenColorFactor{0.0f};         // 0..1
  TextureRef sheenColorTexture;             // RGB, sRGB
  float sheenRoughnessFactor = 0.0f;        // 0..1
  TextureRef sheenRoughnessTexture;         // A
};
struct MaterialIridescence {  // KHR_materials_iridescence
  float iridescenceFactor = 0.0f;           // 0..1
  TextureRef iridescenceTexture;            // R
  float iridescenceIor = 1.3f;              // >= 1: the thin film's
  float iridescenceThicknessMinimum = 100.0f;  // nm, >= 0
  float iridescenceThicknessMaximum = 400.0f;  // nm, >= 0
  TextureRef iridescenceThicknessTexture;   // G: mixes minimum (0) to maximum (1)
};
struct MaterialAnisotropy {  // KHR_materials_anisotropy
  float anisotropyStrength = 0.0f;          // 0..1
  float anisotropyRotation = 0.0f;          // radians, counter-clockwise from the tangent
  TextureRef anisotropyTexture;             // RG: direction in tangent space (-1..1), B: strength
};
struct MaterialTransmission {  // KHR_materials_transmission
  float transmissionFactor = 0.0f;          // 0..1
  TextureRef transmissionTexture;           // R
};
struct MaterialVolume {  // KHR_materials_volume
  float thicknessFactor = 0.0f;             // >= 0, in the mesh's own units
  TextureRef thicknessTexture;              // G
  float attenuationDistance = std::numeric_limits<float>::infinity();  // > 0; infinity: no attenuation
  glm::vec3 attenuationColor{1.0f};         // 0..1
};

struct Material {
  std::string name;
  glm::vec4 baseColorFactor{1.0f};  // linear RGBA, 0..1
  float metallicFactor = 1.0f;      // 0..1
  float roughnessFactor = 1.0f;     // 0..1
  glm::vec3 emissiveFactor{0.0f};   // linear RGB, >= 0
  float normalScale = 1.0f;
  float occlusionStrength = 1.0f;  // 0..1
  bool doubleSided = false;
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;  // MASK only: alpha = baseColorFactor.a x texture alpha x COLOR_0 alpha; 0..1
  TextureRef baseColorTexture;          // sRGB
  TextureRef metallicRoughnessTexture;  // G = roughness, B = metallic (see roughnessFromGlossiness)
  TextureRef normalTexture;             // tangent space
  TextureRef occlusionTexture;          // R
  TextureRef emissiveTexture;           // sRGB
  bool unlit = false;  // KHR_materials_unlit: lit = base colour (factor x texture x COLOR_0), untouched by light
  float ior = 1.5f;    // KHR_materials_ior: >= 1 (glTF's 0, a perfect mirror's F0 of 1, is kept as 0)
  // KHR_materials_pbrSpecularGlossiness with a specularGlossinessTexture:
  // metallicRoughnessTexture is that texture and roughnessFactor its
  // glossinessFactor, so roughness = 1 - roughnessFactor x texture A and
  // metallic = metallicFactor (0). Without the texture the loader stores
  // roughness 1 - glossiness and this stays false.
  bool roughnessFromGlossiness = false;
  std::optional<MaterialSpecular> specular;
  std::optional<MaterialClearcoat> clearcoat;
  std::optional<MaterialSheen> sheen;
  std::optional<MaterialIridescence> iridescence;
  std::optional<MaterialAnisotropy> anisotropy;
  std::optional<MaterialTransmission> transmission;
  std::optional<MaterialVolume> volume;

  bool emissive() const { return emissiveFactor != glm::vec3(0.0f); }
  bool masked() const { return alphaMode == AlphaMode::Mask; }
  bool blended() const { return alphaMode == AlphaMode::Blend; }
  // Drawn by the transmission pass (KHR_materials_transmission with a
  // non-zero factor): not alphaMode BLEND (the blend pass draws it without
  // transmission, which is named) nor unlit (the specification excludes it).
  bool transmissive() const {
    return transmission && transmission->transmissionFactor > 0.0f && !blended() && !unlit;
  }
};

// What a primitive's indices list: triangles (3 each; glTF's strips and fans
// become lists), line segments (2 each; LINE_STRIP and LINE_LOOP become
// lists) or points (1 each). Lines and points are drawn 1 pixel wide.
enum class PrimitiveMode { Triangles, Lines, Points };

// One triangle, line or point list (geometry only; the material is the instance's). After
// loading it is always indexed and always has normals; texcoords and
// tangents are present only if the file had them (or a material drawn with
// it needs them), so the G-buffer shader is built for what exists.
struct Primitive {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;    // same count as positions, unit length
  std::vector<glm::vec2> texcoords;  // TEXCOORD_0; empty or same count
  // TEXCOORD_1, only when a material drawn with the primitive samples it
  // (zeros where the file has none, as for TEXCOORD_0); empty or same count.
  std::vector<glm::vec2> texcoords1;
  std::vector<glm::vec4> tangents;   // xyz + handedness w; empty or same count
  std::vector<glm::vec4> colors;     // COLOR_0, linear RGBA (A = 1 for VEC3); empty or same count
  std::vector<std::uint32_t> indices;
  Bounds bounds;  // in the primitive's own space
  PrimitiveMode mode = PrimitiveMode::Triangles;  // lines and points: normals 0 where the file gives none
};

// A primitive placed in the world by the flattened node hierarchy, with
// the material its glTF primitive names.
struct Instance {
  int primitive = 0;
  glm::mat4 worldFromLocal{1.0f};
  int material = -1;  // index into Scene::materials; -1 = glTF's default material
  // What the ids target numbers the instance by: indices into Scene's
  // meshInstanceNames, meshNames and meshPrimitiveNames (-1: none, id 0 like
  // the background). A mesh instance is one placement of a mesh (a glTF
  // node, or one EXT_mesh_gpu_instancing copy of it): a segmentation mask's
  // object.
  int meshInstance = -1;
  int mesh = -1;
  int meshPrimitive = -1;  // the glTF mesh primitive, numbered across all meshes
};

// One entry of an ids table: a name, and where it is in the file (-1 where
// not from a file: built-in scenes, SceneBuilder).
struct IdName {
  std::string name;
  int index = -1;     // glTF node (mesh instances), mesh (meshes, primitives) or material index
  int subIndex = -1;  // mesh instances: the EXT_mesh_gpu_instancing copy; primitives: the index within the mesh
};

// The matrix that carries normals from local to world space: the cofactor
// matrix of the upper 3x3 (the inverse transpose times the determinant, up
// to sign), which unlike the inverse is defined for a singular transform (a
// node scaled to zero along one axis); callers normalise.
glm::mat3 normalMatrix(const glm::mat4& worldFromLocal);

// True when the transform mirrors (negative determinant): glTF then swaps
// which winding is the front face.
bool mirrors(const glm::mat4& worldFromLocal);

struct Camera {
  enum class Projection { Perspective, Orthographic };
  std::string name;
  Projection projection = Projection::Perspective;
  float yfov = 0.8f;         // radians, perspective only
  float aspectRatio = 0.0f;  // 0 = take the image's
  float xmag = 1.0f;         // half width, orthographic only
  float ymag = 1.0f;         // half height, orthographic only
  float znear = 0.0f;        // 0 = fit to the scene bounds
  float zfar = 0.0f;         // 0 = fit to the scene bounds (glTF: infinite)
  glm::mat4 worldFromCamera{1.0f};
};

// KHR_lights_punctual, in its units: candela for point and spot lights, lux
// for directional ones.
struct Light {
  enum class Type { Directional, Point, Spot };
  std::string name;
  Type type = Type::Point;
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
  float range = 0.0f;  // 0 = infinite
  float innerConeAngle = 0.0f;
  float outerConeAngle = 0.7853982f;       // pi/4, glTF's default
  glm::vec3 position{0.0f};                // world; point and spot
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // world, unit; directional and spot
  bool castsShadows = true;
};

// The procedural sky that lights the scene from everywhere (image-based
// ambient), unless Scene::environment replaces it. It depends only on the
// direction's height, which lets the prefiltered sky be a small 2D table
// (docs/PIPELINE.md).
struct Sky {
  glm::vec3 zenith{0.35f, 0.5f, 0.8f};   // linear radiance straight up
  glm::vec3 horizon{0.8f, 0.85f, 0.9f};  // linear radiance at the horizon
  glm::vec3 ground{0.25f, 0.22f, 0.2f};  // linear radiance below the horizon
  float intensity = 1.0f;                // multiplies all three
};

// An equirectangular HDR environment map (`--environment FILE`,
// headlight/environment.hpp): linear RGB radiance, width = 2 x height, rows
// top first. Texel (x, y) of a W x H map covers azimuth phi = 2 pi ((x+0.5)/W
// - 0.5) about +Y and polar angle theta = pi (y+0.5)/H from +Y; direction
// (sin theta sin phi, cos theta, -sin theta cos phi): the top row is up, the
// image's centre looks along -Z (where the fitted camera looks) and +X lies
// to its right. When present it replaces the procedural sky as the ambient
// light and the background.
struct EnvironmentMap {
  std::string source;      // the file's path
  std::string sourceHash;  // hex fingerprint of the decoded texels (tables are cached by it)
  int width = 0;           // 2 x height
  int height = 0;
  std::vector<float> rgb;  // width x height x 3, finite, >= 0
};

// A glTF feature the file uses that Headlight does not render (or only
// approximates), named once per feature with how many elements use it and
// the first of them, so that a picture is never silently wrong.
struct IgnoredFeature {
  std::string feature;                     // "KHR_materials_sheen", "alphaMode BLEND", "COLOR_0", "mode POINTS"
  std::string noun;                        // what uses it: "material", "primitive", "node"; empty: the file
  std::size_t count = 0;                   // how many of them
  std::string first;                       // the first, as messages name it: "material 2 'Cloth'"
  std::string effect = "is not rendered";  // or "is not played", "is approximated"

  // "KHR_materials_sheen on 3 materials (first: material 2 'Cloth') is not rendered"
  std::string describe() const;
};

struct Scene {
  std::string source;      // file path, or "builtin:<name>"
  std::string sourceHash;  // hex fingerprint of the file's bytes (or the builtin's name and version)
  std::vector<Primitive> primitives;
  std::vector<Material> materials;
  std::vector<ImageData> images;
  std::vector<Instance> instances;
  // The ids target's names (Frame::idNames): what Instance::meshInstance,
  // mesh and meshPrimitive index.
  std::vector<IdName> meshInstanceNames;
  std::vector<IdName> meshNames;
  std::vector<IdName> meshPrimitiveNames;
  std::vector<Camera> cameras;
  std::vector<Light> lights;
  Sky sky;
  // Null: the procedural sky lights the scene. Shared: a batch's scenes hold
  // one decoded map.
  std::shared_ptr<const EnvironmentMap> environment;
  std::vector<IgnoredFeature> ignored;  // glTF only; in the order first met
  // glTF KHR_materials_variants' names, in file order (SceneLoadOptions::materialVariant picks one).
  std::vector<std::string> materialVariants;
  // glTF animations in file order (SceneLoadOptions::animation picks one).
  struct Animation {
    std::string name;  // "" where unnamed
    float end = 0.0f;  // seconds: the latest keyframe time its samplers declare (their input's max)
  };
  std::vector<Animation> animations;
  int animation = -1;          // the one the scene is posed by (SceneLoadOptions::animation), -1: none
  float animationTime = 0.0f;  // and at what time, seconds
  // "animation 0 'Walk' at 1.25 s", or "" for the static pose.
  std::string poseDescription() const;

  Bounds worldBounds() const;
  bool hasEmissive() const;
  bool hasBlended() const;  // an instance's material is alphaMode BLEND
  std::size_t triangleCount() const;  // as drawn: per instance (lines and points are not triangles)
};

}  // namespace HEADLIGHT_PUBLIC
