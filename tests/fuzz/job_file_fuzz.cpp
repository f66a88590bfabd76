// libFuzzer target for the job-file parser (issue 15): each input is a job
// file's text, parsed line by line as `headlight render --jobs` does, then
// checked for output-folder clashes. A bad line becomes a job with an error
// (and a clash a SettingsError): the expected answers. A crash, a hang, an
// exception of another kind or a sanitizer report is a finding. Built and
// run by tools/fuzz.sh (FUZZ_TARGET=job-file).
#include <cstdint>
#include <string>

#include "batch_plan.hpp"
#include "headlight/error.hpp"
#include "job_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::vector<headlight::cli::Job> jobs =
      headlight::cli::parseJobLines(text, "fuzz.jsonl", headlight::RenderSettings{});
  try {
    headlight::cli::checkDistinctOutDirs(jobs);
  } catch (const headlight::SettingsError&) {
  }
  return 0;
}
