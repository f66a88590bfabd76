// The frame-target table (headlight/targets.hpp). Common to every row's
// thresholds:
//  - failPercent 0.5 (ssgi 1): a silhouette pixel can flip between geometry
//    and background on another rasterizer (tie-breaking, interpolation), and
//    a flipped pixel can take any error; 0.5 % is a few times the share of
//    silhouette pixels in the builtin scenes at 64x48 and above.
//  - failMean: those flipped pixels may differ, but not without limit: the
//    mean over all pixels stays within what 0.5 % of full-scale flips add
//    (about fail, or 0.5 % of the metric's full scale where that is larger).
//  - hardFail / hardWarn off (inf) for the same reason; same-driver suites
//    can pass --hardfail.
//  - warnPercent 0 (idiff's): WARN means "something exceeds the noise floor
//    somewhere; look at diff.png", which is what warn is for.
#include "headlight/targets.hpp"

#include <algorithm>

namespace headlight {
namespace {

constexpr DiffThresholds thresholds(double warn, double fail, double failPercent, double failMean) {
  DiffThresholds t;
  t.warn = warn;
  t.fail = fail;
  t.failPercent = failPercent;
  t.failMean = failMean;
  return t;
}

constexpr std::string_view kPositionChannels[] = {"position.X", "position.Y", "position.Z", "A"};
constexpr std::string_view kNormalChannels[] = {"normal.X", "normal.Y", "normal.Z"};
constexpr std::string_view kAlbedoChannels[] = {"albedo.R", "albedo.G", "albedo.B"};
constexpr std::string_view kMaterialChannels[] = {"material.metallic", "material.roughness", "material.occlusion"};
constexpr std::string_view kDepthChannels[] = {"depth.Z"};
constexpr std::string_view kEmissiveChannels[] = {"emissive.R", "emissive.G", "emissive.B"};
constexpr std::string_view kSsgiChannels[] = {"ao.Y",  "indirect.R",    "indirect.G",    "indirect.B",
                                              "sky.Y", "indirectFar.R", "indirectFar.G", "indirectFar.B",
                                              "specular.Y"};
constexpr std::string_view kLitChannels[] = {"R", "G", "B", "A"};
constexpr std::string_view kCoverageChannels[] = {"coverage.Y"};
constexpr std::string_view kTransmissionChannels[] = {"transmission.R", "transmission.G", "transmission.B",
                                                      "transmission.thickness"};
constexpr std::string_view kIridescenceChannels[] = {"iridescence.factor", "iridescence.thickness", "iridescence.ior",
                                                     "iridescence.baseIor"};
constexpr std::string_view kSpecularChannels[] = {"specularF0.R", "specularF0.G", "specularF0.B", "specular"};
constexpr std::string_view kClearcoatChannels[] = {"clearcoat", "clearcoatRoughness", "clearcoatNormal.U",
                                                   "clearcoatNormal.V"};
constexpr std::string_view kSheenChannels[] = {"sheen.R", "sheen.G", "sheen.B", "sheenRoughness"};
constexpr std::string_view kIdsChannels[] = {"instance.id", "mesh.id", "material.id", "primitive.id"};
constexpr std::string_view kAnisotropyChannels[] = {"anisotropy.X", "anisotropy.Y", "anisotropy.Z",
                                                    "anisotropyStrength"};

using M = DiffMetric;
using E = ExrStorage;
using L = PngLook;

const FrameTarget kTargets[] = {
    {"position", &Frame::position, kPositionChannels, E::Float, M::RelativeToScene, thresholds(1e-5, 1e-3, 0.5, 5e-3),
     "world position, A = 1 on geometry. float32 (GPU and EXR): half's 11 bits are too few far from the origin. "
     "Error over the view's far distance: drivers interpolate a few float ulps apart (< 1e-5); 1e-3 of the view "
     "depth is a real geometry or camera change; a silhouette flip can cost ~1, so the mean allows 5e-3. "
     "Coverage A compared absolutely.",
     L::Range},
    {"normal", &Frame::normal, kNormalChannels, E::Half, M::AngleDegrees, thresholds(0.1, 1.0, 0.5, 1.0),
     "world unit normal. Angle in degrees: half storage quantizes unit vectors to ~0.03 deg; 1 deg moves a sharp "
     "highlight, and normal-map or TBN bugs cost many degrees. Components would weigh the axes unequally.",
     L::Signed},
    {"albedo", &Frame::albedo, kAlbedoChannels, E::Half, M::Absolute, thresholds(2e-3, 1e-2, 0.5, 1e-2),
     "linear base colour, 0..1, from 8-bit sRGB textures: one 8-bit step is 3e-4..9e-3 linear, so texture "
     "filtering on another GPU moves values by up to ~1e-2; more is a material or texture change.",
     L::Color},
    {"material", &Frame::material, kMaterialChannels, E::Half, M::Absolute, thresholds(2e-3, 1e-2, 0.5, 1e-2),
     "metallic/roughness/occlusion stored in 8 bits (step 1/255 = 3.9e-3): any step warns, more than two steps "
     "fails.",
     L::Values},
    {"depth", &Frame::depth, kDepthChannels, E::Float, M::RelativeToScene, thresholds(1e-5, 1e-3, 0.5, 5e-3),
     "view-space depth (distance along -Z), far plane on background; float32 like position. Error over the far "
     "distance: depth precision scales with distance.",
     L::Depth},
    {"emissive", &Frame::emissive, kEmissiveChannels, E::Radiance, M::RelativeToValue,
     thresholds(2e-3, 2e-2, 0.5, 2e-2),
     "emitted radiance, only for scenes that glow. HDR (emissiveStrength can be large): absolute below 1, relative "
     "above; half storage (radiance-precision half) rounds at 2.4e-4 relative, 2 % is about the smallest change "
     "visible after tonemapping.",
     L::Radiance},
    {"sheen", &Frame::sheen, kSheenChannels, E::Half, M::Absolute, thresholds(2e-3, 1e-2, 0.5, 1e-2),
     "KHR_materials_sheen's colour (linear, 0..1) and roughness, only for scenes with sheen; 0 where a material has "
     "none. Stored like albedo (sRGB8 colour, 8-bit roughness) from 8-bit textures and factors: one step is "
     "3e-4..9e-3 linear, so filtering on another GPU moves values by up to ~1e-2; more is a material change.",
     L::Color},
    {"anisotropy", &Frame::anisotropy, kAnisotropyChannels, E::Half, M::Absolute, thresholds(2e-3, 2e-2, 0.5, 1e-2),
     "KHR_materials_anisotropy's direction in world space (unit, perpendicular to the normal; 0 where strength is "
     "0) and strength 0..1, only for scenes with anisotropy. Half storage rounds components by ~5e-4; the "
     "direction comes from the tangent frame, which drivers interpolate a little apart at silhouettes, and 0.02 is "
     "about 1 degree of it; the strength comes from 8-bit textures and factors (one step 3.9e-3).",
     L::Signed},
    {"ssgi", &Frame::ssgi, kSsgiChannels, E::Radiance, M::Absolute, thresholds(5e-3, 5e-2, 1.0, 2e-2),
     "AO within R, one-bounce indirect within R, sky visibility at any distance, indirect from beyond R, and the "
     "specular lobe's sky visibility (the kernel methods: AO), 0..~1; absent with SSGI off. Three GPU textures (ao "
     "+ indirect, sky + indirectFar, specular). Seeded and repeatable on one "
     "driver, but one of 64 kernel samples "
     "landing on another pixel moves AO by 1/64; 0.05 is about three such flips or a visible shade, and sky.Y is "
     "held to the same: its long-range samples flip the same way, one slab of a 32-sector mask moves it by ~1/32. "
     "1 % of pixels: samples flip at every depth discontinuity.",
     L::Grey},
    {"lit", &Frame::lit, kLitChannels, E::Radiance, M::Flip, thresholds(0.02, 0.1, 0.5, 0.005),
     "linear HDR radiance, A = coverage (absolute); half, or float with radiance-precision float. HDR-FLIP (0..1), the "
     "difference a viewer flipping between "
     "the images sees over the exposures that span the golden's range: brightness errors the eye ignores cost "
     "little, and a wrong pixel's error spreads over its neighbours. Reruns and osmesa against EGL give 0 "
     "(llvmpipe); 0.02 is far below a visible change; a pixel above 0.1 may be noticed; 0.5 % of pixels for "
     "silhouette flips; mean 0.005 is a third of the smallest setting change measured (spheres 128x96 with "
     "--ssgi-resolution half: mean 0.015, 3.4 % of pixels > 0.1; cornell with --ssgi-steps 4: 0.043).",
     L::Radiance},
    {"coverage", &Frame::coverage, kCoverageChannels, E::Half, M::Absolute, thresholds(2e-3, 1e-2, 0.5, 1e-2),
     "alphaMode BLEND surfaces' accumulated alpha 1 - prod(1 - a) over the pixel, 0..1, whatever lies behind them; "
     "only for scenes that blend. Alpha comes from 8-bit textures and factors (one step 3.9e-3), like albedo: any "
     "step warns, more than two fail.",
     L::Grey},
    {"transmission", &Frame::transmission, kTransmissionChannels, E::HalfWhereItFits, M::RelativeToValue,
     thresholds(2e-3, 1e-2, 0.5, 1e-2),
     "KHR_materials_transmission: the share of the opaque image behind that came through the nearest "
     "transmissive surface (0..1 per channel), and the path length through its volume (world units, 0 for thin "
     "walls); only for scenes that transmit; half, or float when a path length exceeds half's 65504. A product of "
     "8-bit base colour and transmission texture, the split-sum "
     "table and Beer-Lambert: one 8-bit step is 3.9e-3, so any step warns and more than two fail; relative above 1 "
     "for path lengths, whose scale is the scene's.",
     L::Values},
    {"iridescence", &Frame::iridescence, kIridescenceChannels, E::Half, M::RelativeToValue,
     thresholds(2e-3, 1e-2, 0.5, 1e-2),
     "KHR_materials_iridescence's film as the lighting passes read it: strength (factor x texture, 0..1), "
     "thickness in nm (minimum..maximum by the thickness texture), the film's IOR and the base's; only for scenes "
     "with an iridescent material. Absolute below 1, relative above: the strength comes from 8-bit textures and "
     "factors (one step 3.9e-3, like material), the thickness from an 8-bit texture between two bounds (one step "
     "of a 200..600 nm range is 0.4 % at 400 nm) and half storage rounds at 4.9e-4 relative: any step warns, more "
     "than two fail.",
     L::Range},
    {"specular", &Frame::specular, kSpecularChannels, E::Half, M::Absolute, thresholds(1e-3, 1e-2, 0.5, 1e-2),
     "KHR_materials_ior / _specular: the dielectric F0 colour min(((ior-1)/(ior+1))^2 specularColor, 1) and the "
     "specular weight, 0..1; only for scenes with the lobe (0.04 and 1 for materials without it). Half floats "
     "hold both to 5e-4; their textures are 8-bit: a weight step is 3.9e-3 and an sRGB colour step moves an F0 of "
     "0.04 by up to 4e-4 (1 by up to 1e-2). Warn at 1e-3 (a changed F0 of 0.04 is 2.5 %), fail at two weight steps.",
     L::Color},
    {"clearcoat", &Frame::clearcoat, kClearcoatChannels, E::Half, M::Absolute, thresholds(2e-3, 1e-2, 0.5, 1e-2),
     "KHR_materials_clearcoat: coat factor and perceptual roughness, 0..1, and the coat's normal as octahedral "
     "U/V in -1..1; only for scenes with a coat (factor 0 elsewhere). Factor and roughness come from 8-bit "
     "textures (step 3.9e-3), like material: any step warns, more than two fail. 1e-2 in U or V turns the normal "
     "by at most ~0.6 degrees, below normal.exr's 1 degree; a coat normal-map bug costs far more.",
     L::Values},
    {"ids", &Frame::ids, kIdsChannels, E::Uint32, M::Mismatch, thresholds(0.5, 0.5, 0.5, 5e-3),
     "what each pixel shows, as integers: the mesh instance (a node's placement of a mesh, one per "
     "EXT_mesh_gpu_instancing copy), the glTF mesh, the material and the mesh primitive, each 1 + its index in "
     "frame.json's ids tables; 0 on background. uint32 in the file. A label has no nearer or farther wrong "
     "value, so a pixel is right or wrong: any wrong pixel warns, and more than 0.5 % fail (a silhouette pixel "
     "flips between surfaces on another rasterizer, as in the other targets); the mean error is the share of "
     "wrong pixels, held to the same 0.5 %. Opaque and masked surfaces only.",
     L::Labels},
};

// preview.png: what a person looks at, 8-bit sRGB after tone mapping.
constexpr std::string_view kPreviewChannels[] = {"R", "G", "B", "A"};
const FrameTarget kPreviewTarget{
    "preview",
    nullptr,
    kPreviewChannels,
    E::Half,
    M::Flip,
    thresholds(0.02, 0.1, 0.5, 0.005),
    "8-bit sRGB after tone mapping (written beside the EXRs, not read back). LDR-FLIP of the decoded colours: "
    "what a viewer sees on a display; the thresholds are lit's, for the same reasons."};

const FrameTarget kUnknownTarget{
    "",
    nullptr,
    {},
    E::Half,
    M::Absolute,
    DiffThresholds{},
    "not a headlight target: idiff's defaults (absolute, warn = fail = 1e-6, no allowance)."};

}  // namespace

std::span<const FrameTarget> frameTargets() { return kTargets; }

const FrameTarget* findFrameTarget(std::string_view name) {
  const auto found = std::find_if(std::begin(kTargets), std::end(kTargets),
                                  [&](const FrameTarget& target) { return target.name == name; });
  return found == std::end(kTargets) ? nullptr : &*found;
}

const FrameTarget& unknownTargetRow() { return kUnknownTarget; }

const FrameTarget& previewTargetRow() { return kPreviewTarget; }

std::vector<std::pair<std::string, const ImageF*>> Frame::targets() const {
  std::vector<std::pair<std::string, const ImageF*>> list;
  for (const FrameTarget& target : frameTargets())
    if (!(this->*target.image).empty()) list.emplace_back(target.name, &(this->*target.image));
  return list;
}

}  // namespace headlight
