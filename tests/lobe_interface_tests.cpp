// The lobe interface's composition, without GL: lobeDefines gives each
// lobe with GLSL hooks a slot in row order and writes the LOBES_* macros as
// the calls of the lobes that have each hook, and the shader loader's
// #include_lobes expands exactly the variant's lobe files
// (docs/PIPELINE.md, "What a lobe is made of"). The renders that prove the
// hooks compute what the lobes did before are the parity tests
// (sheen_anisotropy_parity_tests.cpp, iridescence_parity_tests.cpp,
// specular_clearcoat_parity_tests.cpp).
#include <doctest/doctest.h>

#include <algorithm>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "frame/frame_plan.hpp"
#include "gl/shader_library.hpp"
#include "headlight/error.hpp"

namespace headlight {
namespace {

bool has(const std::vector<std::string>& defines, const std::string& define) {
  return std::find(defines.begin(), defines.end(), define) != defines.end();
}

// The define that starts with `macro` (a hook's macro and its calls).
std::string macro(const std::vector<std::string>& defines, const std::string& name) {
  for (const std::string& define : defines)
    if (define.starts_with(name + "(") || define.starts_with(name + " ") || define == name) return define;
  return {};
}

// The files buildShaderSource expanded, from its "// file N: name" lines.
std::vector<std::string> expandedFiles(const std::string& source) {
  std::vector<std::string> files;
  for (std::size_t at = source.find("// file "); at != std::string::npos; at = source.find("// file ", at + 1)) {
    const std::size_t colon = source.find(": ", at), end = source.find('\n', at);
    files.push_back(source.substr(colon + 2, end - colon - 2));
  }
  return files;
}

bool expands(const std::vector<std::string>& files, const std::string& file) {
  return std::find(files.begin(), files.end(), file) != files.end();
}

}  // namespace

TEST_CASE("lobe interface: a scene without lobes gets no lobe define (glsl/lobes.glsl stands in)") {
  CHECK(lobeDefines(0).empty());
}

TEST_CASE("lobe interface: each hooked lobe has a slot in row order and its hooks' calls, no other's") {
  const std::vector<std::string> defines = lobeDefines(lobeBit(Lobe::Sheen) | lobeBit(Lobe::Iridescence));
  CHECK(has(defines, "HAS_SHEEN_LOBE"));
  CHECK(has(defines, "HAS_IRIDESCENCE_LOBE"));
  CHECK(!has(defines, "HAS_ANISOTROPY_LOBE"));
  CHECK(has(defines, "SHEEN_LOBE_SLOT 0"));
  CHECK(has(defines, "IRIDESCENCE_LOBE_SLOT 1"));
  CHECK(has(defines, "LOBE_SLOTS 2"));
  CHECK(has(defines, "LOBE_NAMES sheen iridescence"));
  // Sheen layers, iridescence changes the Fresnel: each macro calls only the lobes with its hook.
  CHECK(macro(defines, "LOBES_LAYER_SCALE") ==
        "LOBES_LAYER_SCALE(s, scale, nDotL) scale *= sheenLobeLayerScale(s, s.lobes[0], nDotL);");
  CHECK(macro(defines, "LOBES_FRESNEL") ==
        "LOBES_FRESNEL(s, fresnel) fresnel = iridescenceLobeFresnel(s, s.lobes[1], fresnel);");
  CHECK(macro(defines, "LOBES_REFLECTION") == "LOBES_REFLECTION(s, reflected)");
  // Every hooked lobe's value is read, made from the material and written to its target.
  CHECK(macro(defines, "LOBES_AT") ==
        "LOBES_AT(lobes, pixel) lobes[0] = texelFetch(sheenLobeTarget, pixel, 0); "
        "lobes[1] = texelFetch(iridescenceLobeTarget, pixel, 0);");
  CHECK(macro(defines, "LOBE_TARGET_OUTPUTS") ==
        "LOBE_TARGET_OUTPUTS layout(location = SHEEN_TARGET_LOCATION) out vec4 sheenLobeOut; "
        "layout(location = IRIDESCENCE_TARGET_LOCATION) out vec4 iridescenceLobeOut;");
}

TEST_CASE("lobe interface: clearcoat, composed by the passes, has its define and no slot") {
  const std::vector<std::string> defines = lobeDefines(lobeBit(Lobe::Clearcoat));
  CHECK(has(defines, "HAS_CLEARCOAT_LOBE"));
  CHECK(!has(defines, "CLEARCOAT_LOBE_SLOT 0"));
  CHECK(has(defines, "LOBE_SLOTS 1"));
  CHECK(has(defines, "LOBE_NAMES"));
  CHECK(macro(defines, "LOBES_APPLY") == "LOBES_APPLY(s)");
}

TEST_CASE("lobe interface: #include_lobes expands the variant's lobe files and no other") {
  const std::vector<std::string> sheen = lobeDefines(lobeBit(Lobe::Sheen));
  const std::vector<std::string> brdf = expandedFiles(detail::buildShaderSource("brdf.glsl", sheen));
  CHECK(expands(brdf, "lobe_sheen.glsl"));
  CHECK(!expands(brdf, "lobe_anisotropy.glsl"));
  CHECK(!expands(brdf, "lobe_sheen_ambient.glsl"));  // ambient.glsl's, after prefilteredSky
  const std::vector<std::string> ambient = expandedFiles(detail::buildShaderSource("ambient.glsl", sheen));
  CHECK(expands(ambient, "lobe_sheen_ambient.glsl"));
  // Anisotropy has no ambient layer: no file, no error.
  const std::vector<std::string> anisotropy =
      expandedFiles(detail::buildShaderSource("ambient.glsl", lobeDefines(lobeBit(Lobe::Anisotropy))));
  CHECK(!expands(anisotropy, "lobe_anisotropy_ambient.glsl"));
  // Without lobes, none of the hooked lobes' files. (The loader expands an
  // #include whatever #ifdef surrounds it, so clearcoat's and transmission's
  // files are there, compiled out.)
  for (const std::string& file : expandedFiles(detail::buildShaderSource("gbuffer.frag", {})))
    for (const char* lobe : {"lobe_specular", "lobe_sheen", "lobe_anisotropy", "lobe_iridescence"})
      CHECK_MESSAGE(!file.starts_with(lobe), file);
}

TEST_CASE("lobe interface: a lobe row's hooks are the hooks its GLSL files define, no more, no fewer") {
  // kLobeRows says which hooks each lobe has; its files define them. A hook
  // defined but not in the row would never be called, one in the row but
  // not defined would not compile: both are caught here, per lobe.
  const std::vector<std::string> all = lobeDefines(lobeBit(Lobe::Count) - 1);
  std::vector<std::string> names;
  {
    const std::string list = macro(all, "LOBE_NAMES");
    std::istringstream words{list.substr(std::string("LOBE_NAMES").size())};
    for (std::string name; words >> name;) names.push_back(name);
  }
  REQUIRE(names.size() == 4);  // specular, sheen, anisotropy, iridescence (clearcoat has no hooks)
  for (const std::string& name : names) {
    // Called: `<name>Lobe<Hook>(` in the LOBES_<HOOK> macros (not the values' macros).
    std::set<std::string> called, defined;
    const std::regex call("\\b" + name + "Lobe([A-Z][A-Za-z]*)\\(");
    for (const std::string& define : all) {
      if (!define.starts_with("LOBES_") || define.starts_with("LOBES_AT") || define.starts_with("LOBES_OF_MATERIAL") ||
          define.starts_with("LOBES_WRITE_TARGETS"))
        continue;
      for (auto it = std::sregex_iterator(define.begin(), define.end(), call); it != std::sregex_iterator(); ++it)
        called.insert((*it)[1]);
    }
    // Defined: a function `<type> <name>Lobe<Hook>(` in lobe_<name>.glsl or its _ambient file.
    const std::regex definition("(?:vec4|vec3|float)\\s+" + name + "Lobe([A-Z][A-Za-z]*)\\(");
    for (const std::string& file : {"lobe_" + name + ".glsl", "lobe_" + name + "_ambient.glsl"}) {
      std::string text;
      try {
        text = std::string(detail::shaderText(file));
      } catch (const GlError&) {
        continue;  // no ambient file
      }
      for (auto it = std::sregex_iterator(text.begin(), text.end(), definition); it != std::sregex_iterator(); ++it)
        defined.insert((*it)[1]);
    }
    INFO("lobe " << name);
    CHECK(!defined.empty());
    CHECK(called == defined);
  }
}

TEST_CASE("lobe interface: a lobe named without its GLSL file is an error naming the file") {
  const std::vector<std::string> defines = {"LOBE_NAMES velvet"};
  CHECK_THROWS_WITH_AS(detail::buildShaderSource("brdf.glsl", defines), doctest::Contains("lobe_velvet.glsl"), GlError);
}

}  // namespace headlight
