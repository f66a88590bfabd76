// Finding and loading the image module, and the forwarders that stand in
// for its functions in the library and the CLI (image_module.hpp).
#include "image_io/image_module.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <future>
#include <mutex>
#include <vector>

#include "headlight/error.hpp"
#include "io/folder_lock.hpp"

namespace headlight::detail {
namespace {

namespace fs = std::filesystem;

// The folder of the binary (executable, libheadlight.so or the Python
// module) that holds this function.
fs::path ownFolder() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<const void*>(&ownFolder), &info) == 0 || !info.dli_fname) return {};
  std::error_code error;
  // In the executable itself, dli_fname is its argv[0]: a bare name when it was found on PATH (a file
  // manager running headlight-thumbnailer, or `headlight` installed elsewhere): the kernel knows the file.
  if (std::string_view(info.dli_fname).find('/') == std::string_view::npos)
    if (const fs::path exe = fs::read_symlink("/proc/self/exe", error); !error) return exe.parent_path();
  const fs::path self = fs::canonical(info.dli_fname, error);
  return error ? fs::path(info.dli_fname).parent_path() : self.parent_path();
}

std::vector<fs::path> candidatePaths() {
  if (const char* explicitPath = std::getenv("HEADLIGHT_IMAGE_MODULE"); explicitPath && *explicitPath)
    return {explicitPath};
  const fs::path own = ownFolder();
  const fs::path libdir = HEADLIGHT_INSTALL_LIBDIR;  // relative to the prefix, e.g. lib/x86_64-linux-gnu
  return {own / kImageModuleFile, own / "headlight" / kImageModuleFile, own.parent_path() / kImageModuleFile,
          own.parent_path() / libdir / "headlight" / kImageModuleFile,
          fs::path(HEADLIGHT_INSTALL_PREFIX) / libdir / "headlight" / kImageModuleFile};
}

const ImageModuleTable* loadImageModule() {
  std::string tried;
  for (const fs::path& path : candidatePaths()) {
    std::error_code error;
    if (!fs::exists(path, error)) {
      tried += "\n  " + path.string() + ": not there";
      continue;
    }
    // RTLD_LOCAL: OpenImageIO's symbols stay out of the global scope, where
    // they could bind to an embedding application's own copy. RTLD_LAZY:
    // functions bind on first call, as when linked; binding all of OpenImageIO's
    // ~260 libraries now cost 42 ms more (hyperfine, dlopen alone: 319 against
    // 277 ms). The module is linked with --no-undefined, so nothing is left
    // to fail later.
    void* handle = dlopen(path.c_str(), RTLD_LAZY | RTLD_LOCAL);
    if (!handle) throw IoError(path.string() + ": cannot load the image module: " + dlerror());
    const auto entry = reinterpret_cast<ImageModuleEntry>(dlsym(handle, kImageModuleEntry));
    if (!entry) throw IoError(path.string() + ": not a Headlight image module (no " + kImageModuleEntry + ")");
    // The table is checked before any of its functions is called: a module
    // whose entry returns NULL, or a table of another size or version, is
    // refused with its path. Beyond that a module is trusted: a corrupt file
    // that passes these checks runs its own code (docs/RELIABILITY.md).
    const ImageModuleTable* table = entry();
    if (!table) throw IoError(path.string() + ": broken image module: " + kImageModuleEntry + "() returned no table");
    if (table->abi != kImageModuleAbi || table->tableSize != sizeof(ImageModuleTable))
      throw IoError(path.string() + ": image module from another build (interface " + std::to_string(table->abi) +
                    ", table of " + std::to_string(table->tableSize) + " bytes; this build needs interface " +
                    std::to_string(kImageModuleAbi) + ", " + std::to_string(sizeof(ImageModuleTable)) + " bytes)");
    const void* const functions[] = {reinterpret_cast<const void*>(table->writeFrame),
                                     reinterpret_cast<const void*>(table->writeExr),
                                     reinterpret_cast<const void*>(table->writePreview),
                                     reinterpret_cast<const void*>(table->readSettingAttributes),
                                     reinterpret_cast<const void*>(table->diffImages),
                                     reinterpret_cast<const void*>(table->diffDirectories),
                                     reinterpret_cast<const void*>(table->writeDiffImages),
                                     reinterpret_cast<const void*>(table->decodeTexture),
                                     reinterpret_cast<const void*>(table->decodeEnvironment)};
    for (const void* function : functions)
      if (!function) throw IoError(path.string() + ": broken image module: its table has a null function");
    return table;  // never unloaded: OpenImageIO keeps threads and caches
  }
  throw IoError(std::string("cannot write or read images: the image module ") + kImageModuleFile +
                " (OpenImageIO) was not found; looked at:" + tried + "\n  (set HEADLIGHT_IMAGE_MODULE to its path)");
}

std::mutex loadMutex;
std::shared_future<const ImageModuleTable*> loading;  // guarded by loadMutex

std::shared_future<const ImageModuleTable*> startLoading() {
  const std::lock_guard<std::mutex> lock(loadMutex);
  if (!loading.valid()) loading = std::async(std::launch::async, loadImageModule).share();
  return loading;
}

}  // namespace

const ImageModuleTable& imageModule() { return *startLoading().get(); }

std::string decodeTexture(const unsigned char* bytes, std::size_t size, TextureDecodeLimits& limits,
                          DecodedTexture& texture, bool& overBudget) {
  return imageModule().decodeTexture(bytes, size, limits, texture, overBudget);
}

std::string decodeEnvironment(const char* path, std::uint64_t maxBytes, int maxSide, DecodedEnvironment& map) {
  return imageModule().decodeEnvironment(path, maxBytes, maxSide, map);
}

}  // namespace headlight::detail

namespace headlight {

using detail::imageModule;

void preloadImageIo() { detail::startLoading(); }

std::vector<WrittenFile> writeFrame(const Frame& frame, const std::filesystem::path& outDir,
                                    const OutputOptions& options) {
  // Taken on this side of the module: the lock's per-process count must be
  // the one the CLI's own lock (held from before the render) added to.
  const detail::OutputFolderLock lock(outDir, options.waitForFolder, options.waitForFolderSeconds);
  // Written through the lock's descriptor (the folder locked, even if its
  // name moved), reported under the name the caller gave.
  std::vector<WrittenFile> written;
  try {
    written = imageModule().writeFrame(frame, lock.directory(), options);
  } catch (const IoError& error) {
    throw IoError(lock.named(error.what(), outDir), error.settings());
  }
  for (WrittenFile& file : written) {
    file.path = outDir / file.path.filename();
    file.summary = lock.named(file.summary, outDir);
  }
  return written;
}

WrittenFile writeExr(const Frame& frame, const ImageF& image, const std::filesystem::path& path, bool halfFloat,
                     const ExrAttributes& extra, ExrCompression compression, NonFinitePolicy nonFinite) {
  return imageModule().writeExr(frame, image, path, halfFloat, extra, compression, nonFinite);
}

WrittenFile writePreview(const Frame& frame, const std::filesystem::path& path) {
  return imageModule().writePreview(frame, path);
}

std::map<std::string, std::string> readSettingAttributes(const std::filesystem::path& exr) {
  return imageModule().readSettingAttributes(exr);
}

DiffResult diffImages(const std::filesystem::path& a, const std::filesystem::path& b, const DiffOptions& options) {
  return imageModule().diffImages(a, b, options);
}

DirectoryDiff diffDirectories(const std::filesystem::path& a, const std::filesystem::path& b,
                              const DiffOptions& options) {
  return imageModule().diffDirectories(a, b, options);
}

std::vector<std::filesystem::path> writeDiffImages(const DiffResult& result, const std::filesystem::path& exrPath) {
  return imageModule().writeDiffImages(result, exrPath);
}

}  // namespace headlight
