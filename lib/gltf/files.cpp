#include "gltf/files.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>

namespace headlight::gltf {

namespace fs = std::filesystem;

namespace {

// tinygltf's messages are newline-separated lines; a SceneError is one line.
std::string oneLine(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) {
    text.pop_back();
  }
  std::string::size_type newline;
  while ((newline = text.find('\n')) != std::string::npos) {
    text.replace(newline, 1, "; ");
  }
  return text;
}

// tinygltf reaches the file system only through these callbacks. They keep
// every URI inside the asset's folder (unless allowed), skip tinygltf's
// default wordexp() shell expansion of file names taken from the file, and
// skip its fallback of looking in the current directory.
struct FileAccess {
  fs::path assetFolder;   // canonical
  std::string uriPrefix;  // assetFolder + "/": what tinygltf puts before a URI
  bool allowExternalPaths = false;
  std::string refusal;  // set when a URI was refused; reported after parsing
  std::string problem;  // set when a URI names something that is not a file, or a data URI is malformed
};

bool isInside(const fs::path& path, const fs::path& folder) {
  auto [folderEnd, pathPosition] = std::mismatch(folder.begin(), folder.end(), path.begin(), path.end());
  return folderEnd == folder.end();
}

std::string expandFilePath(const std::string& path, void*) { return path; }

// tinygltf joins the asset folder and the URI even when the URI is absolute
// ("/assets//data/x.png"); an absolute URI means itself.
std::string effectivePath(const std::string& path, const FileAccess& access) {
  if (path.rfind(access.uriPrefix, 0) == 0 && path.size() > access.uriPrefix.size() &&
      path[access.uriPrefix.size()] == '/') {
    return path.substr(access.uriPrefix.size());
  }
  return path;
}

// Records (and returns true for) a URI outside the asset folder while that is
// not allowed, so that the error names the rule rather than "file not found".
bool refuseOutside(const std::string& path, FileAccess& access) {
  if (access.allowExternalPaths) {
    return false;
  }
  const std::string target = effectivePath(path, access);
  std::error_code canonicalError;
  const fs::path resolved = fs::weakly_canonical(target, canonicalError);
  if (!canonicalError && isInside(resolved, access.assetFolder)) {
    return false;
  }
  const std::string uri = path.rfind(access.uriPrefix, 0) == 0 ? path.substr(access.uriPrefix.size()) : path;
  if (access.refusal.empty()) {
    access.refusal = "URI '" + uri + "' resolves to " + resolved.string() + ", outside the asset folder " +
                     access.assetFolder.string() +
                     "; pass allow-external-paths (SceneLoadOptions::allowExternalPaths) to allow it";
  }
  return true;
}

// tinygltf decodes data URIs of six MIME types itself (PNG, JPEG, BMP, GIF,
// octet-stream, gltf-buffer); any other (image/webp, image/ktx2, ...) it
// takes for a file name, URL-decoded, and joins to the asset folder. Such a
// path reaches the callbacks below as <assetFolder>/data:...: its payload is
// decoded here. The URL decoding turned each '+' of the base64 into a space
// (a WebP data URI was refused as "File not found"); base64 has no space,
// so a space is a '+'.
std::optional<std::string> dataUriOf(const std::string& path, const FileAccess& access) {
  if (path.rfind(access.uriPrefix, 0) != 0 || path.compare(access.uriPrefix.size(), 5, "data:") != 0) {
    return std::nullopt;
  }
  return path.substr(access.uriPrefix.size());
}

// The bytes of `uri` ("data:<type>;base64,<payload>"), or the problem.
std::string decodeDataUri(std::string uri, std::vector<unsigned char>& bytes) {
  const std::string shown = quotedName(uri);
  const std::size_t comma = uri.find(',');
  if (comma == std::string::npos || comma < 7 || uri.compare(comma - 7, 7, ";base64") != 0) {
    return "data URI " + shown + " is not base64 (expected data:<type>;base64,<payload>)";
  }
  std::string payload = uri.substr(comma + 1);
  std::replace(payload.begin(), payload.end(), ' ', '+');
  const std::size_t end = payload.find_last_not_of('=');
  const bool alphabet =
      std::all_of(payload.begin(), end == std::string::npos ? payload.begin() : payload.begin() + long(end) + 1,
                  [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '/'; });
  if (payload.empty() || !alphabet || payload.size() - (end + 1) > 2) {
    return "data URI " + shown + " has a payload that is not base64";
  }
  // tinygltf's decoder, through the one type it decodes whatever the bytes are.
  std::string mimeType;
  if (!tinygltf::DecodeDataURI(&bytes, mimeType, "data:application/octet-stream;base64," + payload, 0, false)) {
    return "data URI " + shown + " decodes to nothing";
  }
  return {};
}

// What a path that exists but is not a regular file is, for the message.
std::string kindOf(const fs::file_status& status) {
  switch (status.type()) {
    case fs::file_type::directory:
      return "a folder";
    case fs::file_type::fifo:
      return "a FIFO";
    case fs::file_type::socket:
      return "a socket";
    case fs::file_type::block:
    case fs::file_type::character:
      return "a device";
    default:
      return "not a regular file";
  }
}

bool fileExists(const std::string& path, void* userData) {
  auto& access = *static_cast<FileAccess*>(userData);
  // tinygltf also tries "./<uri>"; only the asset-relative candidate counts.
  if (path.rfind(access.uriPrefix, 0) != 0) {
    return false;
  }
  if (dataUriOf(path, access)) {
    return true;  // readWholeFile decodes it
  }
  if (refuseOutside(path, access)) {
    return false;
  }
  std::error_code error;
  const fs::file_status status = fs::status(effectivePath(path, access), error);
  if (fs::is_regular_file(status)) {
    return true;
  }
  // Named, where tinygltf would say "File not found" of a folder or a FIFO.
  if (!error && fs::exists(status) && access.problem.empty()) {
    access.problem =
        "URI '" + path.substr(access.uriPrefix.size()) + "' is " + kindOf(status) + ", not a file that can be read";
  }
  return false;
}

bool readWholeFile(std::vector<unsigned char>* bytes, std::string* error, const std::string& path, void* userData) {
  auto& access = *static_cast<FileAccess*>(userData);
  if (const std::optional<std::string> uri = dataUriOf(path, access)) {
    const std::string problem = decodeDataUri(*uri, *bytes);
    if (problem.empty()) {
      return true;
    }
    if (access.problem.empty()) {
      access.problem = problem;
    }
    *error = problem;
    return false;
  }
  if (refuseOutside(path, access)) {
    *error = access.refusal;
    return false;
  }
  std::ifstream file(effectivePath(path, access), std::ios::binary);
  if (!file) {
    *error = "cannot open " + path;
    return false;
  }
  bytes->assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
  return true;
}

struct ImageDecoding {
  const tinygltf::Model* model = nullptr;  // the model tinygltf is filling
  std::string failure;                     // set when an image is refused
};

// tinygltf passes an image stored in a bufferView as a pointer into the
// buffer without checking the view's range, so the range is checked here,
// before the first byte is touched.
std::string checkImageBufferView(const tinygltf::Model& model, const tinygltf::Image& image) {
  const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(image.bufferView)];
  const std::size_t bufferSize = model.buffers[static_cast<std::size_t>(view.buffer)].data.size();
  if (view.byteOffset > bufferSize || view.byteLength > bufferSize - view.byteOffset) {
    return "its bufferView " + std::to_string(image.bufferView) + " spans bytes " + std::to_string(view.byteOffset) +
           ".." + std::to_string(view.byteOffset + view.byteLength) + " of buffer " + std::to_string(view.buffer) +
           ", which has " + std::to_string(bufferSize);
  }
  return {};
}

// tinygltf calls this while it parses; it only keeps the encoded bytes, so
// that nothing is decoded before the whole file's structure has been checked
// (readImages in gltf/materials.cpp decodes them last).
bool keepEncodedImage(tinygltf::Image* image, const int imageIndex, std::string* error, std::string*, int, int,
                      const unsigned char* bytes, int size, void* userData) {
  auto& decoding = *static_cast<ImageDecoding*>(userData);
  std::string problem;
  if (image->bufferView >= 0) {
    problem = checkImageBufferView(*decoding.model, *image);
  }
  if (problem.empty() && size <= 0) {
    problem = "it is empty";
  }
  if (problem.empty()) {
    image->image.assign(bytes, bytes + size);
    image->width = image->height = -1;  // not decoded yet
    image->component = 0;
    return true;
  }
  decoding.failure =
      "image " + std::to_string(imageIndex) + (image->name.empty() ? "" : " '" + image->name + "'") + ": " + problem;
  if (error != nullptr) {
    *error += decoding.failure + "\n";
  }
  return false;
}

fs::path canonicalFolderOf(const fs::path& path) {
  std::error_code error;
  const fs::path canonical = fs::weakly_canonical(fs::absolute(path, error), error);
  return (error ? fs::absolute(path, error).lexically_normal() : canonical).parent_path();
}

// Debian's libdraco.so exports a tinygltf of its own (another version, built
// with Draco), and tinygltf's calls bind to whichever library was loaded
// first. Bound to Draco's, parsing writes a Model of another layout and
// corrupts memory; so that binding is refused, once, with the cause.
void checkTinygltfBinding(const std::string& file) {
  static const std::string bound = [] {
    bool (tinygltf::TinyGLTF::*entry)(tinygltf::Model*, std::string*, std::string*, const char*, unsigned int,
                                      const std::string&, unsigned int) = &tinygltf::TinyGLTF::LoadASCIIFromString;
    void* address = nullptr;
    std::memcpy(&address, &entry, sizeof address);  // the Itanium ABI: a non-virtual member's first word
    Dl_info info{};
    return dladdr(address, &info) != 0 && info.dli_fname != nullptr ? std::string(info.dli_fname) : std::string();
  }();
  if (bound.find("libdraco") != std::string::npos) {
    throw SceneError(file + ": tinygltf's functions are bound to " + bound +
                     "'s copy of tinygltf, not libtinygltf.so's; link libtinygltf before libdraco");
  }
}

}  // namespace

std::vector<unsigned char> readAssetBytes(const fs::path& path, const std::string& file, const std::string& extension) {
  std::error_code error;
  if (!fs::exists(path, error)) {
    throw SceneError(file + ": no such file");
  }
  if (!fs::is_regular_file(path, error)) {
    throw SceneError(file + ": not a regular file, expected a .gltf or .glb file");
  }
  if (extension != ".gltf" && extension != ".glb") {
    throw SceneError(file + ": extension '" + extension + "' is not glTF, expected .gltf or .glb");
  }
  std::ifstream stream(path, std::ios::binary);
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(stream)), std::istreambuf_iterator<char>());
  if (!stream.good() && !stream.eof()) {
    throw SceneError(file + ": cannot be read");
  }
  // tinygltf's size arguments are 32-bit.
  if (bytes.size() >= std::numeric_limits<unsigned int>::max()) {
    throw SceneError(file + ": " + std::to_string(bytes.size()) + " bytes, expected less than 4 GiB");
  }
  return bytes;
}

void parseSandboxed(tinygltf::Model& model, const std::vector<unsigned char>& bytes, bool binary, const fs::path& path,
                    bool allowExternalPaths, const std::string& file, std::string& warnings) {
  checkTinygltfBinding(file);
  FileAccess access;
  access.assetFolder = canonicalFolderOf(path);
  access.uriPrefix = access.assetFolder.string();
  if (access.uriPrefix.empty() || access.uriPrefix.back() != '/') {
    access.uriPrefix += '/';
  }
  access.allowExternalPaths = allowExternalPaths;

  tinygltf::TinyGLTF parser;
  parser.SetFsCallbacks({&fileExists, &expandFilePath, &readWholeFile, nullptr, &access});
  ImageDecoding decoding{&model, {}};
  parser.SetImageLoader(&keepEncodedImage, &decoding);
  std::string errors;
  const std::string baseDir = access.assetFolder.string();
  const bool parsed =
      binary ? parser.LoadBinaryFromMemory(&model, &errors, &warnings, bytes.data(),
                                           static_cast<unsigned int>(bytes.size()), baseDir)
             : parser.LoadASCIIFromString(&model, &errors, &warnings, reinterpret_cast<const char*>(bytes.data()),
                                          static_cast<unsigned int>(bytes.size()), baseDir);
  // Our own findings come first: they name the element precisely, where
  // tinygltf's follow-on messages may not.
  if (!access.refusal.empty()) {
    throw SceneError(file + ": " + access.refusal, {"allow-external-paths"});
  }
  if (!access.problem.empty()) {
    throw SceneError(file + ": " + access.problem);
  }
  if (!decoding.failure.empty()) {
    throw SceneError(file + ": " + decoding.failure);
  }
  warnings = oneLine(warnings);
  if (!parsed) {
    throw SceneError(file + ": tinygltf cannot parse it: " + oneLine(errors) +
                     (warnings.empty() ? "" : " (warnings: " + warnings + ")"));
  }
}

}  // namespace headlight::gltf
