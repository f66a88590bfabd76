#pragma once
// What the SSGI report programs (ssgi-flip-report, ssgi-accuracy-report)
// share: their render settings from the command line, and HDR-FLIP's mean.
#include <map>
#include <string>

#include "diff/flip.hpp"
#include "headlight/error.hpp"
#include "headlight/frame.hpp"
#include "headlight/settings.hpp"

namespace headlight::report {

// Settings of `size` x `size` pixels with the arguments from `first` on,
// each `name=value` (a settings-table row, e.g. ssgi-thickness=0.05). One
// sample a pixel unless they say otherwise, as bench and tune render: the
// reference traces each pixel's centre, and an antialiased edge against it
// is an error of the comparison, not of the SSGI (at 8 samples it put
// builtin:slats' HDR-FLIP at 0.0571 against 0.0441).
inline RenderSettings settingsFromArguments(int argc, char** argv, int first, int size) {
  RenderSettings settings;
  settings.width = settings.height = size;
  settings.antialiasSamples = 1;
  std::map<std::string, std::string> values;
  for (int i = first; i < argc; ++i) {
    const std::string argument = argv[i];
    const auto equals = argument.find('=');
    if (equals == std::string::npos) throw SettingsError("expected name=value, got '" + argument + "'");
    values[argument.substr(0, equals)] = argument.substr(equals + 1);
  }
  applySettingsText(settings, values);
  return settings;
}

inline double meanFlip(const ImageF& reference, const ImageF& test) {
  const flip::RgbView a{reference.pixels.data(), reference.width, reference.height, reference.channelCount()};
  const flip::RgbView b{test.pixels.data(), test.width, test.height, test.channelCount()};
  return flip::hdrFlip(a, b).mean;
}

}  // namespace headlight::report
