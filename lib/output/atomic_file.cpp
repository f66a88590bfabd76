#include "output/atomic_file.hpp"

#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include <fstream>
#include <random>
#include <string>

#include "headlight/error.hpp"

namespace headlight::detail {
namespace {

namespace fs = std::filesystem;

// Hidden, ending in .tmp, unique per process and call.
fs::path temporaryPathFor(const fs::path& path) {
  thread_local std::mt19937 rng(std::random_device{}());
  std::string name = ".";
  name += path.filename().string();
  (name += '.') += std::to_string(::getpid());
  (name += '-') += std::to_string(rng());
  name += ".tmp";
  return path.parent_path() / name;
}

}  // namespace

void writeAtomically(const fs::path& path, const std::function<void(const fs::path&)>& write) {
  const fs::path temporary = temporaryPathFor(path);
  try {
    write(temporary);
    std::error_code error;
    fs::rename(temporary, path, error);
    if (error) throw IoError(path.string() + ": cannot move the finished file into place: " + error.message());
  } catch (...) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw;
  }
}

void writeImageAtomically(const fs::path& path, const OIIO::ImageBuf& buffer, const OIIO::ImageSpec& spec,
                          const char* format) {
  writeAtomically(path, [&](const fs::path& temporary) {
    auto output = OIIO::ImageOutput::create(format);
    if (!output) throw IoError(path.string() + ": OpenImageIO has no " + format + " writer: " + OIIO::geterror());
    if (!output->open(temporary.string(), spec) || !buffer.write(output.get()) || !output->close())
      throw IoError(path.string() + ": writing failed: " + output->geterror());
  });
}

void writeTextAtomically(const fs::path& path, std::string_view text) {
  writeAtomically(path, [&](const fs::path& temporary) {
    std::ofstream out(temporary);
    out << text;
    out.close();
    if (!out) throw IoError(path.string() + ": writing failed");
  });
}

}  // namespace headlight::detail
