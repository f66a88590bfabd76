#pragma once
// Every texture a material may sample, one row each: where Material keeps
// it, its texture unit, its colour space, the G-buffer feature bits that
// build it into a shader variant (HAS_<define>_TEXTURE, <define>_TEXCOORD_1)
// and its KHR_texture_transform rows in the MaterialBlock. The upload, the
// G-buffer and blend passes' bindings and the variants' #defines all walk
// this one table, so a material extension's texture is a row.
#include <array>
#include <cstdint>
#include <span>

#include "headlight/scene.hpp"
#include "shared_layout.h"

namespace headlight {

// A set of GBufferFeature bits (below); 64: the KHR_materials_* textures
// need more than 32.
using FeatureBits = std::uint64_t;

// Which optional inputs a G-buffer shader variant reads; a bit set, built
// into the shader as #defines.
enum GBufferFeature : FeatureBits {
  kFeatureTexcoords = FeatureBits{1} << 0,
  kFeatureTangents = FeatureBits{1} << 1,
  kFeatureBaseColorTexture = FeatureBits{1} << 2,
  kFeatureMetallicRoughnessTexture = FeatureBits{1} << 3,
  kFeatureNormalTexture = FeatureBits{1} << 4,
  kFeatureOcclusionTexture = FeatureBits{1} << 5,
  kFeatureEmissiveTexture = FeatureBits{1} << 6,
  kFeatureAlphaMask = FeatureBits{1} << 7,     // alphaMode MASK: discard below the cutoff
  kFeatureVertexColors = FeatureBits{1} << 8,  // COLOR_0 multiplies base colour and alpha
  kFeatureTexcoords1 = FeatureBits{1} << 9,  // the primitive has TEXCOORD_1 (a material drawn with it samples that set)
  kFeatureTextureTransform = FeatureBits{1} << 10,  // KHR_texture_transform: some texture's UVs go through its matrix
  kFeatureUnlit = FeatureBits{1} << 11,             // KHR_materials_unlit: flagged in the material target's A
  // The texture reads TEXCOORD_1 instead of TEXCOORD_0, one bit per texture.
  kFeatureBaseColorTexcoord1 = FeatureBits{1} << 12,
  kFeatureMetallicRoughnessTexcoord1 = FeatureBits{1} << 13,
  kFeatureNormalTexcoord1 = FeatureBits{1} << 14,
  kFeatureOcclusionTexcoord1 = FeatureBits{1} << 15,
  kFeatureEmissiveTexcoord1 = FeatureBits{1} << 16,
  // KHR_materials_pbrSpecularGlossiness's texture in the metallic-roughness
  // slot: roughness = 1 - factor x its A (Material::roughnessFromGlossiness).
  // After the extension textures' bits (material_textures.cpp).
  kFeatureRoughnessFromGlossiness = FeatureBits{1} << 41,
};

enum class MaterialTexture {
  BaseColor,
  MetallicRoughness,
  Normal,
  Occlusion,
  Emissive,
  // The KHR_materials_* textures, in the order of their units (29..40).
  Specular,              // KHR_materials_specular (A)
  SpecularColor,         // KHR_materials_specular (RGB, sRGB)
  Clearcoat,             // KHR_materials_clearcoat (R)
  ClearcoatRoughness,    // KHR_materials_clearcoat (G)
  ClearcoatNormal,       // KHR_materials_clearcoat (tangent space)
  SheenColor,            // KHR_materials_sheen (RGB, sRGB)
  SheenRoughness,        // KHR_materials_sheen (A)
  Iridescence,           // KHR_materials_iridescence's iridescenceTexture (R)
  IridescenceThickness,  // and its iridescenceThicknessTexture (G)
  Anisotropy,            // KHR_materials_anisotropy (RG direction, B strength)
  Transmission,          // KHR_materials_transmission's transmissionTexture (R)
  Thickness,             // KHR_materials_volume's thicknessTexture (G)
  Count
};
inline constexpr std::size_t kMaterialTextureCount = std::size_t(MaterialTexture::Count);

struct MaterialTextureRow {
  MaterialTexture id;
  const char* define;  // BASE_COLOR: HAS_BASE_COLOR_TEXTURE, BASE_COLOR_TEXCOORD_1, BASE_COLOR_SET (gbuffer.frag)
  int unit;            // gpu::kUnit*Texture
  bool srgb;           // colour data: sampled through an sRGB view
  FeatureBits feature;    // the texture is read
  FeatureBits texcoord1;  // it reads TEXCOORD_1
  // The reference in a material; null when the material lacks the extension.
  const TextureRef* (*ref)(const Material&);
  glm::vec4 gpu::MaterialBlock::*transformU;
  glm::vec4 gpu::MaterialBlock::*transformV;
};

// Every row, in MaterialTexture order.
std::span<const MaterialTextureRow> materialTextureRows();

}  // namespace headlight
