// libFuzzer target for the settings-file parser (issue 15): each input is a
// settings file's text (`name = value` lines, as headlight tune writes),
// applied to default settings as `--settings FILE` does, then validated. A
// SettingsError is the expected answer to a bad file; anything else escaping,
// a crash or a sanitizer report is a finding. Built and run by tools/fuzz.sh
// (FUZZ_TARGET=settings).
#include <cstdint>
#include <string_view>

#include "headlight/error.hpp"
#include "headlight/output.hpp"
#include "headlight/settings.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  headlight::RenderSettings settings;
  try {
    headlight::applySettingsFileText(settings, std::string_view(reinterpret_cast<const char*>(data), size),
                                     "fuzz.settings");
    settings.validate();
  } catch (const headlight::SettingsError&) {
    return 0;
  }
  // Accepted settings write back to a file whose values read the same (its
  // rows applied over the settings change nothing): an exception here
  // escapes, and libFuzzer reports it.
  headlight::RenderSettings again = settings;
  headlight::applySettingsFileText(again, headlight::settingsFileText(settings, {}), "again.settings");
  if (headlight::settingsAsText(again) != headlight::settingsAsText(settings)) __builtin_trap();
  return 0;
}
