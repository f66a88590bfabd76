#include "support/temp_folder.hpp"

#include <atomic>
#include <fstream>
#include <random>

namespace fs = std::filesystem;

namespace headlight::test {

fs::path freshFolder(std::string_view prefix) {
  // The random part keeps runs apart (ctest runs suites side by side), the
  // counter keeps the folders of one run apart.
  static std::atomic<int> counter{0};
  const fs::path path =
      fs::temp_directory_path() / ("headlight_" + std::string(prefix) + "_" + std::to_string(std::random_device{}()) +
                                   "_" + std::to_string(counter++));
  fs::remove_all(path);
  fs::create_directories(path);
  return path;
}

TempFolder::~TempFolder() {
  std::error_code ignored;
  fs::remove_all(path_, ignored);
}

fs::path TempFolder::write(const std::string& name, const void* bytes, std::size_t size) const {
  const fs::path file = path_ / name;
  fs::create_directories(file.parent_path());
  std::ofstream(file, std::ios::binary).write(static_cast<const char*>(bytes), static_cast<std::streamsize>(size));
  return file;
}

}  // namespace headlight::test
