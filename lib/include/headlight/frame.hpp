#pragma once
// What one render gives back: every target as floats in memory, the view it
// was rendered from, the settings it used (auto values resolved) and where
// the time went. Nothing here touches the GL, so a caller may keep frames
// after the renderer is gone.
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "headlight/camera.hpp"
#include "headlight/export.hpp"
#include "headlight/settings.hpp"

namespace headlight HEADLIGHT_PUBLIC {

// An interleaved float image, rows top first (image order, not GL's).
struct ImageF {
  int width = 0;
  int height = 0;
  std::vector<std::string> channels;  // e.g. {"normal.X", "normal.Y", "normal.Z"}
  std::vector<float> pixels;          // width * height * channels.size()

  bool empty() const { return pixels.empty(); }
  int channelCount() const { return int(channels.size()); }
  float at(int x, int y, int channel) const {
    return pixels[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * channels.size() + std::size_t(channel)];
  }
};

// Work a frame left out because its scene, settings or wanted targets do not
// need it (the renderer's one table of rules, lib/renderer.cpp).
struct SkippedWork {
  std::string work;    // "shadows", "direct", "ssgi", "composite", "sky", "emissive"
  std::string reason;  // "no light casts shadows", "sky intensity 0", ...
};

struct PassTime {
  std::string pass;
  double milliseconds = 0;  // wall time, bounded by glFinish before and after (CPU work included)
  // The GPU's own time for the pass's commands (a GL_TIME_ELAPSED query);
  // negative where the driver reports none.
  double gpuMilliseconds = -1;
  // How a fullscreen pass ran ("fragment" or "compute", --fullscreen-form);
  // empty for the other passes.
  std::string form;
  // What a pass made, where it says (the light field: its probes); `--verbose` prints it.
  std::string detail;
};

// The names behind the ids target's values (Frame::ids): id k >= 1 of a
// kind is entry k - 1 of its table; 0 is the background (and an instance
// that nothing names).
struct IdNames {
  std::vector<IdName> meshInstances;   // Scene::meshInstanceNames
  std::vector<IdName> meshes;          // Scene::meshNames
  std::vector<IdName> materials;       // Scene::materials (index = material), then glTF's default (index -1)
  std::vector<IdName> meshPrimitives;  // Scene::meshPrimitiveNames
};

struct Frame {
  ImageF position;  // position.X/Y/Z world, A = 1 on geometry, 0 on background
  ImageF normal;    // normal.X/Y/Z world, unit length; 0 on background
  ImageF albedo;    // albedo.R/G/B linear base colour
  ImageF material;  // material.metallic, material.roughness, material.occlusion
  ImageF depth;     // depth.Z: view-space depth (distance along -Z), far plane on background
  ImageF emissive;  // emissive.R/G/B; empty when the scene has no emissive material
  // sheen.R/G/B linear sheen colour, sheenRoughness; only for scenes with KHR_materials_sheen
  ImageF sheen;
  // anisotropy.X/Y/Z world direction (unit, 0 where strength is 0), anisotropyStrength; only for scenes with
  // KHR_materials_anisotropy
  ImageF anisotropy;
  ImageF
      ssgi;  // ao.Y, indirect.R/G/B (within R), sky.Y (any distance), indirectFar.R/G/B (beyond R); empty with SSGI off
  ImageF lit;       // R/G/B/A linear HDR; A = coverage, RGB = sky on background
  // Not a target (no file of its own): with antialiasing and a preview
  // background other than the sky, the samples' foreground premultiplied,
  // the mean of lit's RGB x A (R/G/B) and of A; preview.png shows it over
  // the colour or transparent, where lit's RGB would bring the sky behind a
  // silhouette's edge pixels along. Empty otherwise.
  ImageF litForeground;
  ImageF coverage;  // coverage.Y: alphaMode BLEND's accumulated alpha, 1 - prod(1 - a); only for scenes that blend
  // transmission.R/G/B: how much of the opaque image behind came through the
  // nearest KHR_materials_transmission surface; transmission.thickness: its path
  // length through the volume (world units; 0 for thin walls); only for
  // scenes that transmit, with lit
  ImageF transmission;
  // iridescence.factor, .thickness (nm), .ior (the film's), .baseIor (Material::ior):
  // KHR_materials_iridescence's film per pixel; only for scenes with an iridescent material
  ImageF iridescence;
  // specularF0.R/G/B, specular: KHR_materials_ior / _specular's dielectric F0
  // colour and specular weight; only for scenes with the specular lobe.
  ImageF specular;
  // clearcoat, clearcoatRoughness, clearcoatNormal.U/V (the coat's world
  // normal, octahedral-encoded); only for scenes with KHR_materials_clearcoat.
  ImageF clearcoat;
  // instance.id, mesh.id, material.id, primitive.id: what each pixel shows,
  // as integers (exact in float up to 2^24; uint32 in ids.exr), 0 on
  // background; names in idNames. The opaque and masked surfaces the other
  // G-buffer targets hold (alphaMode BLEND's are not in them). Only when
  // wanted (all targets, or named).
  ImageF ids;
  // The ids' names; shared by every frame of one scene. Null without ids.
  std::shared_ptr<const IdNames> idNames;

  CameraView view;
  RenderSettings settings;  // as used: "auto" values resolved to numbers
  std::vector<PassTime> timings;
  std::vector<SkippedWork> skipped;  // in the table's order; what `--verbose` lists
  std::string glRenderer;
  std::string glVersion;
  std::string backend;      // "egl" or "osmesa", and which device
  std::string sceneSource;  // file path or builtin name
  std::string sceneHash;
  std::string scenePose;  // "animation 0 'Walk' at 1.25 s" when posed by one (--animation, --time); "" otherwise
  // glTF features the scene uses that are not rendered, one line each
  // (Scene::ignored, IgnoredFeature::describe()); written to frame.json and
  // the EXRs' headlight:ignored.
  std::vector<std::string> ignored;

  // Every non-empty target with its file stem ("position", ..., "lit"), in
  // the order of frameTargets() (headlight/targets.hpp).
  std::vector<std::pair<std::string, const ImageF*>> targets() const;
};

}  // namespace HEADLIGHT_PUBLIC
