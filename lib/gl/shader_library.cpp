#include "gl/shader_library.hpp"

#include <set>
#include <sstream>

#include "headlight/error.hpp"

namespace headlight::detail {

namespace {

const EmbeddedShader* findShader(std::string_view name) {
  for (const EmbeddedShader& shader : embeddedShaders())
    if (name == shader.name) return &shader;
  return nullptr;
}

}  // namespace

std::string_view shaderText(std::string_view name) {
  if (const EmbeddedShader* shader = findShader(name)) return shader->text;
  throw GlError("shader library: no shader named '" + std::string(name) + "' in glsl/");
}

namespace {

// The variant's lobes with GLSL hooks, from the LOBE_NAMES define that
// lobeDefines writes ("LOBE_NAMES specular sheen"); none without it.
std::vector<std::string> lobeNamesOf(std::span<const std::string> defines) {
  constexpr std::string_view kKey = "LOBE_NAMES";
  std::vector<std::string> names;
  for (const std::string& define : defines) {
    if (!define.starts_with(kKey) || (define.size() > kKey.size() && define[kKey.size()] != ' ')) continue;
    std::istringstream words{define.substr(kKey.size())};
    for (std::string name; words >> name;) names.push_back(name);
  }
  return names;
}

// Expands #include "file" lines, each file at most once, and
// #include_lobes "suffix" lines: glsl/lobe_<name><suffix>.glsl for each lobe
// of LOBE_NAMES in its order, so that the shared files compose a variant's
// lobes without naming them (docs/PIPELINE.md, "What a lobe is made of").
// With an empty suffix the file must exist (a lobe is its GLSL file); with
// another ("_material", "_ambient") a lobe may have none.
void appendExpanded(std::string_view fileName, std::span<const std::string> lobes, std::set<std::string>& included,
                    std::vector<std::string>& fileNames, std::string& out) {
  if (!included.insert(std::string(fileName)).second) return;
  fileNames.emplace_back(fileName);
  const int fileNumber = int(fileNames.size()) - 1;
  std::istringstream lines{std::string(shaderText(fileName))};
  std::string line;
  int lineNumber = 0;
  out += "#line 1 " + std::to_string(fileNumber) + "\n";
  while (std::getline(lines, line)) {
    ++lineNumber;
    const auto first = line.find_first_not_of(" \t");
    // Only #include "file" is ours; #include <...> lines sit in the shared
    // header's C++-only section, which the GLSL preprocessor skips.
    if (first != std::string::npos && line.compare(first, 8, "#include") == 0 && line.find('<') == std::string::npos) {
      const auto open = line.find('"'), close = line.rfind('"');
      if (open == std::string::npos || close < open + (line.compare(first, 14, "#include_lobes") == 0 ? 1 : 2))
        throw GlError(std::string(fileName) + ":" + std::to_string(lineNumber) + ": malformed #include");
      const std::string named = line.substr(open + 1, close - open - 1);
      if (line.compare(first, 14, "#include_lobes") == 0) {
        for (const std::string& lobe : lobes) {
          const std::string file = "lobe_" + lobe + named + ".glsl";
          if (named.empty() || findShader(file)) appendExpanded(file, lobes, included, fileNames, out);
        }
      } else {
        appendExpanded(named, lobes, included, fileNames, out);
      }
      out += "#line " + std::to_string(lineNumber + 1) + " " + std::to_string(fileNumber) + "\n";
      continue;
    }
    out += line;
    out += '\n';
  }
}

GLenum stageOf(std::string_view file) {
  if (file.ends_with(".vert")) return GL_VERTEX_SHADER;
  if (file.ends_with(".frag")) return GL_FRAGMENT_SHADER;
  if (file.ends_with(".comp")) return GL_COMPUTE_SHADER;
  throw GlError("shader library: cannot tell the stage of '" + std::string(file) + "' (.vert, .frag or .comp)");
}

}  // namespace

std::string buildShaderSource(std::string_view fileName, std::span<const std::string> defines) {
  const std::string_view files[] = {fileName};
  return buildShaderSource(files, defines);
}

std::string buildShaderSource(std::span<const std::string_view> files, std::span<const std::string> defines) {
  std::string source = "#version 450 core\n";
  for (const auto& define : defines) source += "#define " + define + "\n";
  std::set<std::string> included;
  std::vector<std::string> fileNames;
  std::string body;
  const std::vector<std::string> lobes = lobeNamesOf(defines);
  for (std::string_view file : files) appendExpanded(file, lobes, included, fileNames, body);
  // Which number is which file, for reading compiler logs.
  for (std::size_t i = 0; i < fileNames.size(); ++i)
    source += "// file " + std::to_string(i) + ": " + fileNames[i] + "\n";
  return source + body;
}

gl::Program buildProgram(std::span<const std::string_view> files, std::span<const std::string> defines) {
  std::vector<StageFiles> stages;
  for (const std::string_view& file : files) stages.push_back({std::span(&file, 1)});
  return buildProgram(stages, defines);
}

gl::Program buildProgram(std::span<const StageFiles> stageFiles, std::span<const std::string> defines) {
  std::vector<gl::Program::Stage> stages;
  for (const StageFiles& files : stageFiles) {
    std::string name;
    for (std::string_view file : files.files) name += (name.empty() ? "" : " + ") + std::string(file);
    if (!defines.empty()) {
      name += " [";
      for (std::size_t i = 0; i < defines.size(); ++i) name += (i ? ", " : "") + defines[i];
      name += "]";
    }
    stages.push_back({stageOf(files.files.back()), name, buildShaderSource(files.files, defines)});
  }
  return gl::Program::link(stages);
}

}  // namespace headlight::detail
