// ssgi-flip-report: for every scene of the stability suite, the mean
// HDR-FLIP of `lit` against the reference's `lit_ref`, with the default SSGI
// and with SSGI off (issue 16: the default must never be worse than no
// SSGI). A measuring tool like stability-report, never run in CI: the
// reference costs minutes. docs/BENCHMARKS.md records its output.
//   build/tests/ssgi-flip-report [SIZE [RAYS [FLAGS...]]]
// SIZE: image width and height (default 128); RAYS: the reference's rays per
// pixel (default 1024); FLAGS: settings applied to the SSGI render only, as
// `name=value` (e.g. ssgi-thickness=0.05), to compare a variant. The
// environment variable SCENES (a substring of the scene's name, e.g.
// "near-wall") limits the report to the scenes that match.
#include <cstdio>
#include <cstdlib>
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
    RenderSettings ssgi = report::settingsFromArguments(argc, argv, 3, size);
    RenderSettings off;
    off.width = off.height = size;
    off.ssgi.enabled = false;
    Context context(ContextOptions{.backend = Backend::Auto, .errorPolicy = GlErrorPolicy::Throw, .eglDeviceName = {}});
    Renderer renderer(context);
    std::printf("| scene | default | --no-ssgi | default - no SSGI | mean lit / reference, default, no SSGI |\n"
                "|---|---:|---:|---:|---|\n");
    std::fflush(stdout);
    const char* only = std::getenv("SCENES");
    for (const SuiteScene& entry : suiteScenes()) try {
      if (only && entry.name.find(only) == std::string::npos) continue;
      renderer.setScene(entry.build());
      const Camera camera = stability::cornellOrbitCamera(entry.orbitDegrees);
      const Camera* chosen = entry.orbitCamera ? &camera : nullptr;
      const Frame withSsgi = renderer.render(ssgi, chosen);
      const Frame without = renderer.render(off, chosen);
      ReferenceSettings settings;
      settings.samplesPerPixel = rays;
      settings.radius = *withSsgi.settings.ssgi.radius;
      const ReferenceImages truth = traceReference(renderer.scene(), withSsgi, settings);
      const double a = report::meanFlip(truth.lit, withSsgi.lit), b = report::meanFlip(truth.lit, without.lit);
      std::printf("| %s | %.5f | %.5f | %+.5f%s | %.3f, %.3f |\n", entry.name.c_str(), a, b, a - b,
                  a > b + 5e-5 ? " (worse)" : "", meanLitRatio(truth.lit, withSsgi.lit),
                  meanLitRatio(truth.lit, without.lit));
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
