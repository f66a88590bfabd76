// A soak, not a test: creates, renders with and destroys a context and
// renderer N times, then renders M frames on one renderer, and prints the
// resident set size along the way. docs/EMBEDDING.md records its figures.
//
//   build/tools/headlight-soak [--backend auto|egl|osmesa] [--cycles 1000] [--renders 10000] [--size 64]
//
// Exit status 1 when the RSS after warm-up grows by more than 5 % over the
// long run of renders.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "headlight/context.hpp"
#include "headlight/error.hpp"
#include "headlight/frame.hpp"
#include "headlight/renderer.hpp"
#include "headlight/scene_loader.hpp"

using namespace headlight;

namespace {

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(values.size() / 2), values.end());
  return values[values.size() / 2];
}

double rssMiB() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return double(resident) * double(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

}  // namespace

int main(int argc, char** argv) try {
  ContextOptions options;
  int cycles = 1000, renders = 10000, size = 64;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i], value = argv[i + 1];
    if (flag == "--backend")
      options.backend = parseBackend(value);
    else if (flag == "--cycles")
      cycles = std::atoi(value.c_str());
    else if (flag == "--renders")
      renders = std::atoi(value.c_str());
    else if (flag == "--size")
      size = std::atoi(value.c_str());
    else
      throw SettingsError("unknown flag " + flag);
  }
  RenderSettings settings;
  settings.width = settings.height = size;
  settings.ssgi.sampleCount = 8;
  const Scene scene = loadScene("builtin:cornell");
  std::printf("start: RSS %.1f MiB\n", rssMiB());

  double cycleWarm = 0;
  for (int cycle = 1; cycle <= cycles; ++cycle) {
    Context context(options);
    Renderer renderer(context);
    renderer.setScene(scene);
    renderer.render(settings);
    if (cycle == 10) cycleWarm = rssMiB();
    if (cycle == 1 || cycle == 10 || cycle % 100 == 0)
      std::printf("create/render/destroy %5d: RSS %.1f MiB (%s)\n", cycle, rssMiB(), context.description().c_str());
  }
  if (cycles >= 10)
    std::printf("create/render/destroy: %d cycles, RSS %.1f MiB after 10, %.1f MiB after %d (%+.1f %%)\n", cycles,
                cycleWarm, rssMiB(), cycles, 100.0 * (rssMiB() - cycleWarm) / cycleWarm);

  Context context(options);
  Renderer renderer(context);
  renderer.setScene(scene);
  double warm = 0;
  const int warmUp = std::min(100, renders);
  std::vector<double> frameMs, readbackMs;  // each render's wall time, and its readback's
  for (int i = 1; i <= renders; ++i) {
    const auto start = std::chrono::steady_clock::now();
    const Frame frame = renderer.render(settings);
    frameMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    for (const PassTime& time : frame.timings)
      if (time.pass == "readback") readbackMs.push_back(time.milliseconds);
    if (i == warmUp) warm = rssMiB();
    if (i == 1 || i == warmUp || i % 1000 == 0) std::printf("render %6d: RSS %.1f MiB\n", i, rssMiB());
  }
  const double growth = 100.0 * (rssMiB() - warm) / warm;
  std::printf("one renderer: %d renders at %dx%d, RSS %.1f MiB after %d, %.1f MiB after %d (%+.1f %%) on %s, %s\n",
              renders, size, size, warm, warmUp, rssMiB(), renders, growth, context.description().c_str(),
              context.renderer().c_str());
  // Every target read back each render: the readback's share of a render (docs/BENCHMARKS.md, "Session 14").
  std::printf("one renderer: median render %.1f ms, of which readback %.1f ms (every target)\n", median(frameMs),
              median(readbackMs));
  return growth > 5.0 ? 1 : 0;
} catch (const Error& error) {
  std::cerr << "headlight-soak: " << error.what() << "\n";
  return 1;
}
