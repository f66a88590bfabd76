// ssgi-flip-report: for every scene of the stability suite, the mean
// HDR-FLIP of `lit` against the reference's `lit_ref`, with the default SSGI
// and with SSGI off (issue 16: the default must never be worse than no
// SSGI). A measuring tool like stability-report, never run in CI: the
// reference costs minutes. docs/BENCHMARKS.md records its output.
//   build/tests/ssgi-flip-report [SIZE [RAYS [FLAGS... [/ FLAGS...]...]]]
// SIZE: image width and height (default 128); RAYS: the reference's rays per
// pixel (default 1024); FLAGS: settings applied to the SSGI render only, as
// `name=value` (e.g. ssgi-thickness=0.05), to compare a variant; a `/` starts
// another variant, each a column against the same reference (the default's
// R). The environment variable SCENES (a substring of the scene's name, e.g.
// "near-wall") limits the report to the scenes that match; MODELS=DIR reports
// the glTF models DIR/NAME/glTF/NAME.gltf (../shared/gltf-conformance) from
// their own or a fitted camera, with the default lights where they have none,
// instead of the stability suite (issue 33, item 3).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "headlight/error.hpp"
#include "headlight/reference.hpp"
#include "headlight/renderer.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/settings.hpp"
#include "stability/report_args.hpp"
#include "stability/stability.hpp"

using namespace headlight;

namespace {

// One scene of the suite as its cases build it; `camera` null: the scene's own.
struct SuiteScene {
  std::string name;
  std::function<Scene()> build;
  bool orbitCamera = false;
  float orbitDegrees = 0;
};

std::vector<SuiteScene> suiteScenes() {
  using namespace stability;
  return {
      {"flat-plane (builtin:plane)", flatPlaneScene},
      {"near-wall (cornell, camera 0.1 from the wall)", nearWallScene},
      {"thin-geometry (builtin:slats)", slatsScene},
      {"screen-edge (builtin:offscreen)", offscreenBoxScene},
      {"depth-step (builtin:depth-step)", depthStepScene},
      {"grazing-floor (builtin:grazing)", grazingFloorScene},
      {"scene-scale 1e-3 (cornell)", [] { return scaledScene(makeBuiltinScene("cornell"), 1e-3f); }},
      {"scene-scale 1e3 (cornell)", [] { return scaledScene(makeBuiltinScene("cornell"), 1e3f); }},
      {"flicker orbit 0 deg (cornell)", [] { return makeBuiltinScene("cornell"); }, true, 0.0f},
      {"flicker orbit 7.5 deg (cornell)", [] { return makeBuiltinScene("cornell"); }, true, 7.5f},
      {"degenerate: NaN vertex", nanVertexScene},
      {"degenerate: zero-area triangles", zeroAreaScene},
      {"degenerate: missing normals", missingNormalsScene},
      {"degenerate: huge coordinates", hugeCoordinateScene},
  };
}

// The models under `folder` laid out as ../shared/gltf-conformance is.
std::vector<SuiteScene> modelScenes(const std::filesystem::path& folder) {
  std::vector<SuiteScene> scenes;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    const std::filesystem::path file = entry.path() / "glTF" / (name + ".gltf");
    if (entry.is_directory() && std::filesystem::exists(file))
      scenes.push_back({name, [file] { return loadScene(file.string()); }});
  }
  std::sort(scenes.begin(), scenes.end(), [](const SuiteScene& a, const SuiteScene& b) { return a.name < b.name; });
  return scenes;
}

// The variants' settings: the arguments from `first` on, split at "/".
std::vector<RenderSettings> variantsFromArguments(int argc, char** argv, int first, int size) {
  std::vector<RenderSettings> variants;
  int start = first;
  for (int i = first; i <= argc; ++i)
    if (i == argc || std::string(argv[i]) == "/") {
      std::vector<char*> group{argv[0]};
      for (int j = start; j < i; ++j) group.push_back(argv[j]);
      variants.push_back(report::settingsFromArguments(int(group.size()), group.data(), 1, size));
      start = i + 1;
    }
  return variants;
}

std::string variantName(int argc, char** argv, int first, std::size_t index) {
  std::string name;
  std::size_t group = 0;
  for (int i = first; i < argc; ++i) {
    if (std::string(argv[i]) == "/") {
      ++group;
      continue;
    }
    if (group == index) name += (name.empty() ? "" : " ") + std::string(argv[i]);
  }
  return name.empty() ? "default" : name;
}

// Mean lit luminance (RGB summed) of `test` over that of `reference`, on the
// pixels the reference covers: below 1, too dark on the whole.
double meanLitRatio(const ImageF& reference, const ImageF& test) {
  double sumTest = 0, sumReference = 0;
  for (int y = 0; y < reference.height; ++y)
    for (int x = 0; x < reference.width; ++x) {
      if (reference.at(x, y, 3) == 0.0f) continue;
      for (int c = 0; c < 3; ++c) sumReference += reference.at(x, y, c), sumTest += test.at(x, y, c);
    }
  return sumReference > 0 ? sumTest / sumReference : 1.0;
}

}  // namespace

int main(int argc, char** argv) {
  const int size = argc > 1 ? std::atoi(argv[1]) : 128;
  const int rays = argc > 2 ? std::atoi(argv[2]) : 1024;
  try {
    if (!referenceAvailable()) {
      std::cerr << "ssgi-flip-report: this build has no Embree reference\n";
      return 77;
    }
    const std::vector<RenderSettings> variants = variantsFromArguments(argc, argv, 3, size);
    RenderSettings off = report::settingsFromArguments(argc, argv, argc, size);
    off.ssgi.enabled = false;
    Context context(ContextOptions{.backend = Backend::Auto, .errorPolicy = GlErrorPolicy::Throw, .eglDeviceName = {}});
    Renderer renderer(context);
    std::string header = "| scene |", rule = "|---|", ratios;
    for (std::size_t v = 0; v < variants.size(); ++v) {
      const std::string name = variantName(argc, argv, 3, v);
      header += " " + name + " | " + name + " - no SSGI |";
      rule += "---:|---:|";
      ratios += name + ", ";
    }
    std::printf("%s --no-ssgi | mean lit / reference: %sno SSGI |\n%s---:|---|\n", header.c_str(), ratios.c_str(),
                rule.c_str());
    std::fflush(stdout);
    const char* only = std::getenv("SCENES");
    const char* models = std::getenv("MODELS");
    for (const SuiteScene& entry : models ? modelScenes(models) : suiteScenes()) try {
        if (only && entry.name.find(only) == std::string::npos) continue;
        renderer.setScene(entry.build());
        const Camera camera = stability::cornellOrbitCamera(entry.orbitDegrees);
        const Camera* chosen = entry.orbitCamera ? &camera : nullptr;
        std::vector<Frame> frames;
        for (const RenderSettings& settings : variants) frames.push_back(renderer.render(settings, chosen));
        const Frame without = renderer.render(off, chosen);
        ReferenceSettings settings;
        settings.samplesPerPixel = rays;
        settings.radius = *frames.front().settings.ssgi.radius;
        const ReferenceImages truth = traceReference(renderer.scene(), frames.front(), settings);
        const double b = report::meanFlip(truth.lit, without.lit);
        std::string row = "| " + entry.name + " |", litRatios;
        char cell[96];
        for (const Frame& frame : frames) {
          const double a = report::meanFlip(truth.lit, frame.lit);
          std::snprintf(cell, sizeof cell, " %.5f | %+.5f%s |", a, a - b, a > b + 5e-5 ? " (worse)" : "");
          row += cell;
          std::snprintf(cell, sizeof cell, "%.3f, ", meanLitRatio(truth.lit, frame.lit));
          litRatios += cell;
        }
        std::printf("%s %.5f | %s%.3f |\n", row.c_str(), b, litRatios.c_str(), meanLitRatio(truth.lit, without.lit));
        std::fflush(stdout);
      } catch (const Error& error) {  // a degenerate input the renderer refuses (its case expects that)
        std::printf("| %s | refused: %s | | | |\n", entry.name.c_str(), error.what());
      }
  } catch (const Error& error) {
    std::cerr << "ssgi-flip-report: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
