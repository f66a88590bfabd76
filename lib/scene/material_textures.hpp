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

// A set of GBufferFeature bits (lib/scene/gpu_scene.hpp); 64: the
// KHR_materials_* textures need more than 32.
using FeatureBits = std::uint64_t;

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
