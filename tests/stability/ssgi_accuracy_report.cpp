// Issue 16's measures of the SSGI against the ray-traced reference on its
// four scenes, in one run (docs/BENCHMARKS.md): per scene, the HDR-FLIP of
// lit against the reference's lit; the indirect light's relative RMSE, ssgi's
// indirect + indirectFar against the reference's unlimited indirect over the
// geometry pixels (the RMSE of the three channels over the reference's
// mean), and their mean ratio; the sky visibility's RMSE; the AO RMSE at
// R = 0.1 x the scene's diagonal (a second render with that radius against
// the reference's ao.Y traced with it). A second table splits the indirect
// light at the default R: ssgi's indirect (the near field) against the
// reference's indirectR, and indirectFar against indirect - indirectR, each
// as a mean ratio and an RMSE over the reference's mean of that part (a
// second trace, at the default R), and the screen-space bound at that R
// (ReferenceSettings::screenBound, a third trace): its error against the
// truth, the least a method that reads only the screen must make, and ours
// against it; then that split by surface (the floor and the rest). Never
// runs in CI.
//   build/tests/ssgi-accuracy-report [SIZE [RAYS [FLAGS...]]]
// SIZE: image width and height (default 256); RAYS: the reference's rays per
// pixel (default 4096: about 200 s on two cores, three traces a scene); FLAGS: settings of the
// renders as `name=value` (e.g. ssgi-virtual-lights=0), to compare a
// variant. MetalRoughSpheresNoTextures comes from ../shared (or
// $HEADLIGHT_SHARED_DIR); it is left out, and said so, where absent.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "headlight/error.hpp"
#include "headlight/reference.hpp"
#include "headlight/renderer.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/settings.hpp"
#include "stability/report_args.hpp"
#include "support/assets.hpp"

using namespace headlight;

namespace {

constexpr int kIndirect = 1, kSky = 4, kIndirectFar = 5;  // ssgi.exr's channels
constexpr int kReferenceWithinR = 0, kReferenceIndirect = 3;  // indirect_ref's indirectR.R, unlimited indirect.R


struct IndirectError {
  double relativeRmse = 0, ratio = 0, skyRmse = 0;
};

IndirectError indirectError(const Frame& frame, const ReferenceImages& truth) {
  double squared = 0, ours = 0, theirs = 0, sky = 0;
  long values = 0, pixels = 0;
  for (int y = 0; y < frame.ssgi.height; ++y)
    for (int x = 0; x < frame.ssgi.width; ++x) {
      if (frame.position.at(x, y, 3) == 0.0f) continue;
      for (int c = 0; c < 3; ++c) {
        const double a = frame.ssgi.at(x, y, kIndirect + c) + frame.ssgi.at(x, y, kIndirectFar + c);
        const double b = truth.indirect.at(x, y, kReferenceIndirect + c);
        squared += (a - b) * (a - b);
        ours += a;
        theirs += b;
        ++values;
      }
      const double d = double(frame.ssgi.at(x, y, kSky)) - truth.ao.at(x, y, 1);
      sky += d * d;
      ++pixels;
    }
  if (values == 0 || theirs <= 0) return {};
  return {std::sqrt(squared / double(values)) / (theirs / double(values)), ours / theirs,
          std::sqrt(sky / double(pixels))};
}

// Light compared over the geometry pixels, three channels each: mean ratio
// and RMSE / the reference's mean. `ours(x, y, c)` and `theirs(x, y, c)`
// read the two sides.
struct PartError {
  double ratio = 0, relativeRmse = 0;
};
template <typename Ours, typename Theirs>
PartError lightError(const Frame& frame, Ours ours, Theirs theirs) {
  double squared = 0, oursSum = 0, theirsSum = 0;
  long values = 0;
  for (int y = 0; y < frame.position.height; ++y)
    for (int x = 0; x < frame.position.width; ++x) {
      if (frame.position.at(x, y, 3) == 0.0f) continue;
      for (int c = 0; c < 3; ++c) {
        const double a = ours(x, y, c), b = theirs(x, y, c);
        squared += (a - b) * (a - b);
        oursSum += a;
        theirsSum += b;
        ++values;
      }
    }
  if (values == 0 || theirsSum <= 0) return {};
  return {oursSum / theirsSum, std::sqrt(squared / double(values)) / (theirsSum / double(values))};
}

// The indirect light within R (near) or beyond it (far), ours against the reference's.
PartError partError(const Frame& frame, const ReferenceImages& truth, bool far) {
  return lightError(
      frame, [&](int x, int y, int c) { return double(frame.ssgi.at(x, y, (far ? kIndirectFar : kIndirect) + c)); },
      [&](int x, int y, int c) {
        const double withinR = truth.indirect.at(x, y, kReferenceWithinR + c);
        return far ? truth.indirect.at(x, y, kReferenceIndirect + c) - withinR : withinR;
      });
}

// Two references' light (`first` against `truth`), channels from `channel`.
PartError referenceError(const Frame& frame, const ReferenceImages& first, const ReferenceImages& truth, int channel) {
  return lightError(
      frame, [&](int x, int y, int c) { return double(first.indirect.at(x, y, channel + c)); },
      [&](int x, int y, int c) { return double(truth.indirect.at(x, y, channel + c)); });
}

// The split by surface: the floor (world normal within 8 degrees of +Y,
// where builtin:spheres' balls stand) and the rest, each part (within R,
// beyond R) as ours / reference and its squared error's share of the whole
// image's all-distance squared error. Where the error sits, in numbers.
std::string surfaceSplitRows(const std::string& name, const Frame& frame, const ReferenceImages& truth) {
  double total = 0, squared[2][2] = {}, ours[2][2] = {}, theirs[2][2] = {};
  long pixels[2] = {};
  for (int y = 0; y < frame.ssgi.height; ++y)
    for (int x = 0; x < frame.ssgi.width; ++x) {
      if (frame.position.at(x, y, 3) == 0.0f) continue;
      const int surface = frame.normal.at(x, y, 1) > 0.99f ? 0 : 1;
      ++pixels[surface];
      for (int c = 0; c < 3; ++c) {
        const double withinR = truth.indirect.at(x, y, kReferenceWithinR + c);
        const double beyondR = truth.indirect.at(x, y, kReferenceIndirect + c) - withinR;
        const double near = frame.ssgi.at(x, y, kIndirect + c), far = frame.ssgi.at(x, y, kIndirectFar + c);
        const double parts[2][2] = {{near, withinR}, {far, beyondR}};
        for (int part = 0; part < 2; ++part) {
          const double d = parts[part][0] - parts[part][1];
          squared[surface][part] += d * d;
          ours[surface][part] += parts[part][0];
          theirs[surface][part] += parts[part][1];
        }
        const double all = near + far - withinR - beyondR;
        total += all * all;
      }
    }
  std::string rows;
  const char* names[2] = {"floor", "the rest"};
  for (int surface = 0; surface < 2; ++surface) {
    if (pixels[surface] == 0) continue;
    char row[256];
    const auto ratio = [&](int part) {
      return theirs[surface][part] > 0 ? ours[surface][part] / theirs[surface][part] : 0.0;
    };
    const auto share = [&](int part) { return total > 0 ? squared[surface][part] / total : 0.0; };
    std::snprintf(row, sizeof row, "| %s | %s | %ld | %.3f | %.2f | %.3f | %.2f |\n", name.c_str(), names[surface],
                  pixels[surface], ratio(0), share(0), ratio(1), share(1));
    rows += row;
  }
  return rows;
}

double aoRmse(const Frame& frame, const ReferenceImages& truth) {
  double squared = 0;
  long pixels = 0;
  for (int y = 0; y < frame.ssgi.height; ++y)
    for (int x = 0; x < frame.ssgi.width; ++x) {
      const double d = double(frame.ssgi.at(x, y, 0)) - truth.ao.at(x, y, 0);
      squared += d * d;
      ++pixels;
    }
  return std::sqrt(squared / double(pixels));
}

}  // namespace

int main(int argc, char** argv) {
  const int size = argc > 1 ? std::atoi(argv[1]) : 256;
  const int rays = argc > 2 ? std::atoi(argv[2]) : 4096;
  try {
    if (!referenceAvailable()) {
      std::cerr << "ssgi-accuracy-report: this build has no Embree reference\n";
      return 77;
    }
    RenderSettings settings = report::settingsFromArguments(argc, argv, 3, size);
    RenderSettings nearRadius = settings;
    nearRadius.ssgi.radius.reset();
    nearRadius.ssgi.radiusFraction = 0.1f;

    Context context(ContextOptions{.backend = Backend::Auto, .errorPolicy = GlErrorPolicy::Throw, .eglDeviceName = {}});
    Renderer renderer(context);
    std::printf("%dx%d, %d reference rays; %s\n\n", size, size, rays, context.renderer().c_str());
    std::printf("| scene | HDR-FLIP | indirect rel. RMSE | indirect ours / reference | sky RMSE | AO RMSE, R = 0.1 diag |\n"
                "|---|---:|---:|---:|---:|---:|\n");
    std::vector<std::string> scenes = {"builtin:cornell", "builtin:spheres", "builtin:slats"};
    const std::string metalRough = test::metalRoughSpheresGltf().string();
    if (test::exists(metalRough))
      scenes.push_back(metalRough);
    else
      std::printf("(MetalRoughSpheresNoTextures left out: %s is missing)\n", metalRough.c_str());
    std::string splitRows, surfaceRows;
    for (const std::string& scene : scenes) {
      renderer.setScene(loadScene(scene));
      const Frame frame = renderer.render(settings);
      const Frame nearFrame = renderer.render(nearRadius);
      // lit and the unlimited indirect do not depend on R; ao.Y does: traced
      // with the second render's.
      ReferenceSettings reference;
      reference.samplesPerPixel = rays;
      reference.radius = *nearFrame.settings.ssgi.radius;
      const ReferenceImages truth = traceReference(renderer.scene(), frame, reference);
      const IndirectError indirect = indirectError(frame, truth);
      const std::string name = scene == metalRough ? "MetalRoughSpheresNoTextures" : scene;
      std::printf("| %s | %.4f | %.3f | %.3f | %.3f | %.4f |\n", name.c_str(), report::meanFlip(truth.lit, frame.lit),
                  indirect.relativeRmse, indirect.ratio, indirect.skyRmse, aoRmse(nearFrame, truth));
      std::fflush(stdout);
      reference.radius = *frame.settings.ssgi.radius;
      const ReferenceImages split = traceReference(renderer.scene(), frame, reference);
      const PartError nearPart = partError(frame, split, false), farPart = partError(frame, split, true);
      // The screen-space bound at the same R: how far from the truth a method
      // that reads only the screen must stay, and how far ours is from it.
      reference.screenBound = true;
      const ReferenceImages bound = traceReference(renderer.scene(), frame, reference);
      const PartError boundNear = referenceError(frame, bound, split, kReferenceWithinR);
      const PartError boundAll = referenceError(frame, bound, split, kReferenceIndirect);
      const IndirectError oursToBound = indirectError(frame, bound);
      char row[320];
      std::snprintf(row, sizeof row, "| %s | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f |\n",
                    name.c_str(), *frame.settings.ssgi.radius, nearPart.ratio, nearPart.relativeRmse, farPart.ratio,
                    farPart.relativeRmse, boundNear.ratio, boundNear.relativeRmse, boundAll.relativeRmse,
                    oursToBound.relativeRmse);
      splitRows += row;
      surfaceRows += surfaceSplitRows(name, frame, split);
    }
    std::printf(
        "\nThe indirect light split at the default R (ours / reference, and RMSE over the reference's mean of the "
        "part); then the screen-space bound (the reference with only surfaces the frame shows within R): its "
        "within-R light against the truth's, its indirect light (all distances) against the truth's, and ours "
        "against it:\n\n"
        "| scene | R | within R: ratio | rel. RMSE | beyond R: ratio | rel. RMSE | bound within R: ratio | rel. RMSE "
        "| bound, all: rel. RMSE | ours to bound: rel. RMSE |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n%s",
        splitRows.c_str());
    std::printf(
        "\nThe same split by surface (floor: world normal y > 0.99), ours / reference and each part's squared "
        "error as a share of the image's (all distances):\n\n"
        "| scene | surface | pixels | within R: ratio | share | beyond R: ratio | share |\n"
        "|---|---|---:|---:|---:|---:|---:|\n%s",
        surfaceRows.c_str());
  } catch (const Error& error) {
    std::cerr << "ssgi-accuracy-report: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
