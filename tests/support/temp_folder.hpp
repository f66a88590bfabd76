#pragma once
// Scratch space for tests: a fresh folder under the system temp folder whose
// name no other test (or run of the same test) shares.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace headlight::test {

// Makes an empty folder temp/headlight_<prefix>_<random>_<counter> and
// returns its path; the caller removes it when done.
std::filesystem::path freshFolder(std::string_view prefix);

// A fresh folder removed with everything in it when this object dies.
class TempFolder {
 public:
  explicit TempFolder(std::string_view prefix = "test") : path_(freshFolder(prefix)) {}
  ~TempFolder();
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;

  // Writes `bytes` to `name` (relative; parent folders made) and returns its path.
  std::filesystem::path write(const std::string& name, const void* bytes, std::size_t size) const;
  std::filesystem::path write(const std::string& name, const std::string& text) const {
    return write(name, text.data(), text.size());
  }
  std::filesystem::path write(const std::string& name, const std::vector<unsigned char>& bytes) const {
    return write(name, bytes.data(), bytes.size());
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace headlight::test
