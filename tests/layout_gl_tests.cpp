// The shared layout (glsl/shared_layout.h) against what the GL linked:
// walked from the header's own lists, so a new block or texture unit is
// checked without a line here. Each uniform and storage block must be active
// in one of the programs below with the C++ struct's size and its row's
// binding; every sampler of every program must sit on a unit of the list.
#include <doctest/doctest.h>
#include <glad/gl.h>

#include <algorithm>
#include <cstddef>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "frame/frame_plan.hpp"
#include "gl/shader_library.hpp"
#include "passes/fullscreen.hpp"
#include "shared_layout.h"
#include "support/gl.hpp"

namespace headlight {
namespace {

using namespace headlight::test;

// `defines` and lobeDefines(lobes): a lobe's code (its file, its hooks, its
// G-buffer reads and writes) is in a program only with all of them.
std::vector<std::string> withLobes(std::vector<std::string> defines, std::uint32_t lobes) {
  for (std::string& define : lobeDefines(lobes)) defines.push_back(std::move(define));
  return defines;
}
constexpr std::uint32_t kSpecularClearcoat = lobeBit(Lobe::Specular) | lobeBit(Lobe::Clearcoat);
constexpr std::uint32_t kSheenAnisotropy = lobeBit(Lobe::Sheen) | lobeBit(Lobe::Anisotropy);

// Every program the renderer builds, each with the #defines that make all
// of its blocks and samplers active.
struct ProgramSource {
  std::vector<std::string_view> files;
  std::vector<std::string> defines;
};
const std::vector<ProgramSource>& programSources() {
  static const std::vector<ProgramSource> sources = {
      {{"gbuffer.vert", "gbuffer.frag"},
       {"HAS_TEXCOORDS", "HAS_TANGENTS", "HAS_BASE_COLOR_TEXTURE", "HAS_METALLIC_ROUGHNESS_TEXTURE",
        "HAS_NORMAL_TEXTURE", "HAS_OCCLUSION_TEXTURE", "HAS_EMISSIVE_TEXTURE", "HAS_EMISSIVE_TARGET",
        "EMISSIVE_TARGET_LOCATION 4", "ALPHA_MASK", "HAS_VERTEX_COLORS", "HAS_TEXCOORDS_1", "HAS_TEXTURE_TRANSFORM",
        "UNLIT", "BASE_COLOR_TEXCOORD_1", "METALLIC_ROUGHNESS_TEXCOORD_1", "NORMAL_TEXCOORD_1", "OCCLUSION_TEXCOORD_1",
        "EMISSIVE_TEXCOORD_1"}},
      // The transmission pass's forward variant (lib/passes/transmission.hpp).
      {{"gbuffer.vert", "gbuffer.frag"},
       {"TRANSMISSION_FORWARD", "HAS_TEXCOORDS", "HAS_TRANSMISSION_TEXTURE", "HAS_THICKNESS_TEXTURE",
        "HAS_PLANAR_SHADOWS", "HAS_CUBE_SHADOWS", "HAS_SKY"}},
      {{"shadow.vert", "shadow.frag"}, {}},
      {{"shadow.vert", "shadow.frag"}, {"ALPHA_MASK", "HAS_TEXCOORDS", "HAS_BASE_COLOR_TEXTURE", "HAS_VERTEX_COLORS"}},
      {{"shadow.vert", "shadow.frag"},
       {"ALPHA_MASK", "HAS_TEXCOORDS", "HAS_BASE_COLOR_TEXTURE", "HAS_TEXCOORDS_1", "BASE_COLOR_TEXCOORD_1",
        "HAS_TEXTURE_TRANSFORM"}},
      // Transmissive casters into the transmittance maps (lib/passes/shadow.hpp).
      {{"shadow.vert", "shadow_transmittance.frag"},
       {"SHADOW_TRANSMITTANCE", "ALPHA_MASK", "HAS_TEXCOORDS", "HAS_BASE_COLOR_TEXTURE", "HAS_TRANSMISSION_TEXTURE",
        "HAS_VERTEX_COLORS", "HAS_TEXCOORDS_1", "TRANSMISSION_TEXCOORD_1", "HAS_TEXTURE_TRANSFORM"}},
      // The specular and clearcoat lobes (glsl/lobe_*.glsl): their textures and attachments (the lighting
      // passes' reads of them: passSources()).
      {{"gbuffer.vert", "gbuffer.frag"},
       withLobes({"HAS_TEXCOORDS", "HAS_SPECULAR_TEXTURE", "HAS_SPECULAR_COLOR_TEXTURE", "HAS_CLEARCOAT_TEXTURE",
                  "HAS_CLEARCOAT_ROUGHNESS_TEXTURE", "HAS_CLEARCOAT_NORMAL_TEXTURE", "HAS_SPECULAR_TARGET",
                  "SPECULAR_TARGET_LOCATION 4", "HAS_CLEARCOAT_TARGET", "CLEARCOAT_TARGET_LOCATION 5"},
                 kSpecularClearcoat)},
      // KHR_materials_iridescence: the lobe's attachment and its textures.
      {{"gbuffer.vert", "gbuffer.frag"},
       withLobes({"HAS_TEXCOORDS", "HAS_TEXCOORDS_1", "HAS_TEXTURE_TRANSFORM", "HAS_IRIDESCENCE_TARGET",
                  "IRIDESCENCE_TARGET_LOCATION 4", "HAS_IRIDESCENCE_TEXTURE", "HAS_IRIDESCENCE_THICKNESS_TEXTURE",
                  "IRIDESCENCE_TEXCOORD_1"},
                 lobeBit(Lobe::Iridescence))},
      {{"gbuffer.vert", "gbuffer.frag"},
       withLobes({"BLEND_FORWARD", "HAS_SKY", "HAS_TEXCOORDS", "HAS_IRIDESCENCE_TEXTURE",
                  "HAS_IRIDESCENCE_THICKNESS_TEXTURE"},
                 lobeBit(Lobe::Iridescence))},
      // The sheen and anisotropy lobes: their G-buffer targets and textures.
      {{"gbuffer.vert", "gbuffer.frag"},
       withLobes({"HAS_TEXCOORDS", "HAS_SHEEN_TARGET", "SHEEN_TARGET_LOCATION 4", "HAS_SHEEN_COLOR_TEXTURE",
                  "HAS_SHEEN_ROUGHNESS_TEXTURE", "HAS_ANISOTROPY_TARGET", "ANISOTROPY_TARGET_LOCATION 5",
                  "HAS_ANISOTROPY_TEXTURE"},
                 kSheenAnisotropy)},
  };
  return sources;
}

// Every fullscreen pass's body (lib/passes/fullscreen.hpp), with the
// PassOutputs members its passes write and the #defines that make all of its
// inputs active. Each is linked in both forms and accumulating, so the
// entries' own units (the accumulated outputs) are read too.
struct PassSource {
  std::string_view body;
  std::vector<std::string_view> outputs;
  std::vector<std::string> defines;
};
const std::vector<PassSource>& passSources() {
  static const std::vector<PassSource> sources = {
      {"direct_light.glsl",
       {"towardEye", "diffuse"},
       {"HAS_EMISSIVE", "HAS_PLANAR_SHADOWS", "HAS_CUBE_SHADOWS", "HAS_SHADOW_TRANSMITTANCE"}},
      {"direct_light.glsl", {"towardEye"}, withLobes({}, kSpecularClearcoat)},
      {"direct_light.glsl", {"towardEye"}, withLobes({}, lobeBit(Lobe::Iridescence))},
      {"direct_light.glsl", {"towardEye"}, withLobes({}, kSheenAnisotropy)},
      {"ssgi.glsl", {"nearField", "sky", "specular"}, {"METHOD_RADIANCE"}},
      {"ssgi_bitmask.glsl", {"nearField", "farField", "farFieldOverNear", "specular"}, {}},
      {"ssgi_blur.glsl", {"nearField", "sky", "specular", "skyLine"}, {}},
      {"composite.glsl", {"radiance"}, {"HAS_SSGI", "HAS_SKY"}},
      {"composite.glsl", {"radiance"}, {"HAS_SSGI", "HAS_SKY", "HAS_ENVIRONMENT"}},
      {"composite.glsl", {"radiance"}, withLobes({"HAS_SKY"}, kSpecularClearcoat)},
      {"composite.glsl", {"radiance"}, withLobes({"HAS_SSGI", "HAS_SKY"}, lobeBit(Lobe::Iridescence))},
      {"composite.glsl", {"radiance"}, withLobes({"HAS_SKY"}, kSheenAnisotropy)},
      {"brdf_lut.glsl", {"scaleBias"}, {}},
      {"sky_prefilter.glsl", {"radiance"}, {}},
      {"sky_irradiance.glsl", {"irradianceOverPi"}, {}},
      {"antialias.glsl", {"lit"}, {}},
  };
  return sources;
}

gl::Program passProgram(const PassSource& source, PassForm form, bool accumulates) {
  PassEntry entry{form, accumulates, {}};
  for (std::string_view member : source.outputs) entry.outputs.emplace_back(member, GL_RGBA16F);
  return buildPassProgram(source.body, entry, source.defines);
}

struct LinkedProgram {
  std::string name;
  gl::Program program;
};

std::vector<LinkedProgram> linkAll() {
  std::vector<LinkedProgram> programs;
  for (const ProgramSource& source : programSources())
    programs.push_back({std::string(source.files.back()), detail::buildProgram(source.files, source.defines)});
  std::vector<PassSource> sources = passSources();
  // The rows whose pass has no GL code of its own: linked as their rows name them.
  for (const FullscreenPassRow& row : fullscreenPassRows())
    if (!row.body.empty()) sources.push_back({row.body, {row.outputs.begin(), row.outputs.end()}, {}});
  for (const PassSource& source : sources)
    for (PassForm form : {PassForm::Fragment, PassForm::Compute})
      programs.push_back(
          {std::string(source.body) + " (" + std::string(passFormName(form)) + ")", passProgram(source, form, true)});
  return programs;
}

struct BlockFacts {
  GLint size = -1;
  GLint binding = -1;
};

// The block's size and binding in the first program where it is active.
std::optional<BlockFacts> findBlock(const std::vector<LinkedProgram>& programs, GLenum interface, const char* name) {
  for (const LinkedProgram& linked : programs) {
    const GLuint index = glGetProgramResourceIndex(linked.program.id(), interface, name);
    if (index == GL_INVALID_INDEX) continue;
    const GLenum properties[] = {GL_BUFFER_DATA_SIZE, GL_BUFFER_BINDING};
    GLint values[2] = {-1, -1};
    glGetProgramResourceiv(linked.program.id(), interface, index, 2, properties, 2, nullptr, values);
    return BlockFacts{values[0], values[1]};
  }
  return std::nullopt;
}

bool isSampler(GLenum type) {
  switch (type) {
    case GL_SAMPLER_2D:
    case GL_SAMPLER_2D_ARRAY_SHADOW:
    case GL_SAMPLER_CUBE_MAP_ARRAY_SHADOW:
    case GL_SAMPLER_CUBE_MAP_ARRAY:
    case GL_SAMPLER_2D_ARRAY:
    case GL_SAMPLER_CUBE:
    case GL_SAMPLER_3D:
      return true;
    default:
      return false;
  }
}

// The unit each active sampler uniform of `program` is bound to.
std::vector<std::pair<std::string, GLint>> samplerUnits(GLuint program) {
  GLint count = 0;
  glGetProgramInterfaceiv(program, GL_UNIFORM, GL_ACTIVE_RESOURCES, &count);
  std::vector<std::pair<std::string, GLint>> units;
  for (GLint i = 0; i < count; ++i) {
    const GLenum properties[] = {GL_TYPE, GL_LOCATION, GL_NAME_LENGTH};
    GLint values[3] = {};
    glGetProgramResourceiv(program, GL_UNIFORM, GLuint(i), 3, properties, 3, nullptr, values);
    if (!isSampler(GLenum(values[0])) || values[1] < 0) continue;
    std::string name(std::size_t(values[2]), '\0');
    glGetProgramResourceName(program, GL_UNIFORM, GLuint(i), values[2], nullptr, name.data());
    name.resize(name.size() - 1);  // the terminating NUL
    GLint unit = -1;
    glGetUniformiv(program, values[1], &unit);
    units.emplace_back(name, unit);
  }
  return units;
}

}  // namespace

TEST_CASE("shared layout: every listed block is linked with its C++ size and its row's binding") {
  Context& context = sharedContext();
  const std::vector<LinkedProgram> programs = linkAll();
#define HL_CHECK_BLOCK(interface, block, name, value)                                                      \
  {                                                                                                        \
    const std::optional<BlockFacts> facts = findBlock(programs, interface, #block);                        \
    INFO(#block);                                                                                          \
    REQUIRE_MESSAGE(facts, "no linked program has it active: add its pass's program to programSources()"); \
    CHECK(facts->binding == value);                                                                        \
    if (interface == GL_UNIFORM_BLOCK) CHECK(facts->size == GLint(sizeof(gpu::block)));                    \
  }
#define HL_CHECK_UNIFORM_BLOCK(block, name, value) HL_CHECK_BLOCK(GL_UNIFORM_BLOCK, block, name, value)
#define HL_CHECK_STORAGE_BLOCK(block, name, value) HL_CHECK_BLOCK(GL_SHADER_STORAGE_BLOCK, block, name, value)
  HL_UNIFORM_BLOCKS(HL_CHECK_UNIFORM_BLOCK)
  HL_STORAGE_BLOCKS(HL_CHECK_STORAGE_BLOCK)
#undef HL_CHECK_BLOCK
#undef HL_CHECK_UNIFORM_BLOCK
#undef HL_CHECK_STORAGE_BLOCK
  context.checkErrors("querying the linked blocks");
}

TEST_CASE("shared layout: every sampler sits on a listed unit, and every listed unit is read") {
  Context& context = sharedContext();
  const std::vector<LinkedProgram> programs = linkAll();
#define HL_UNIT_VALUE(name, unit) unit,
  const std::set<GLint> listed{HL_TEXTURE_UNITS(HL_UNIT_VALUE)};
#undef HL_UNIT_VALUE
  std::set<GLint> read;
  for (const LinkedProgram& linked : programs) {
    std::set<GLint> inProgram;
    for (const auto& [sampler, unit] : samplerUnits(linked.program.id())) {
      INFO(linked.name << ": " << sampler << " on unit " << unit);
      CHECK(listed.count(unit) == 1);
      CHECK(inProgram.insert(unit).second);  // two samplers of one program never share a unit
      read.insert(unit);
    }
  }
  CHECK(read == listed);
  context.checkErrors("querying the linked samplers");
}

}  // namespace headlight

namespace headlight {
using namespace headlight::test;

namespace {

// What the GL says a uniform block's member offset and the block's size
// are, for a linked program: the std140 layout the GLSL side really has.
GLint blockDataSize(GLuint program, const char* block) {
  const GLuint index = glGetProgramResourceIndex(program, GL_UNIFORM_BLOCK, block);
  REQUIRE(index != GL_INVALID_INDEX);
  const GLenum property = GL_BUFFER_DATA_SIZE;
  GLint size = 0;
  glGetProgramResourceiv(program, GL_UNIFORM_BLOCK, index, 1, &property, 1, nullptr, &size);
  return size;
}

GLint memberOffset(GLuint program, const char* member) {
  const GLuint index = glGetProgramResourceIndex(program, GL_UNIFORM, member);
  REQUIRE(index != GL_INVALID_INDEX);
  const GLenum property = GL_OFFSET;
  GLint offset = -1;
  glGetProgramResourceiv(program, GL_UNIFORM, index, 1, &property, 1, nullptr, &offset);
  return offset;
}

}  // namespace

TEST_CASE("uniform blocks: the linked GLSL layout matches the C++ structs") {
  sharedContext();
  const gl::Program ssgi = passProgram({"ssgi.glsl", {"nearField"}, {}}, PassForm::Fragment, false);
  CHECK(blockDataSize(ssgi.id(), "SsgiBlock") == GLint(sizeof(gpu::SsgiBlock)));
  CHECK(memberOffset(ssgi.id(), "SsgiBlock.radiusWorld") == GLint(offsetof(gpu::SsgiBlock, radiusWorld)));
  CHECK(memberOffset(ssgi.id(), "SsgiBlock.indirectStrength") == GLint(offsetof(gpu::SsgiBlock, indirectStrength)));
  CHECK(memberOffset(ssgi.id(), "SsgiBlock.sampleCount") == GLint(offsetof(gpu::SsgiBlock, sampleCount)));
  CHECK(memberOffset(ssgi.id(), "SsgiBlock.downsample") == GLint(offsetof(gpu::SsgiBlock, downsample)));
  CHECK(blockDataSize(ssgi.id(), "FrameBlock") == GLint(sizeof(gpu::FrameBlock)));
  CHECK(memberOffset(ssgi.id(), "FrameBlock.projection") == GLint(offsetof(gpu::FrameBlock, projection)));
  CHECK(memberOffset(ssgi.id(), "FrameBlock.viewport") == GLint(offsetof(gpu::FrameBlock, viewport)));

  const std::string_view gbufferFiles[] = {"gbuffer.vert", "gbuffer.frag"};
  const gl::Program gbuffer = detail::buildProgram(gbufferFiles);
  // The instances' transforms are std430 and read through a struct: its stride and members.
  const GLuint objects =
      glGetProgramResourceIndex(gbuffer.id(), GL_BUFFER_VARIABLE, "ObjectBuffer.objectList[0].normalFromLocal");
  REQUIRE(objects != GL_INVALID_INDEX);
  const GLenum objectProperties[] = {GL_OFFSET, GL_TOP_LEVEL_ARRAY_STRIDE};
  GLint objectValues[2] = {-1, -1};
  glGetProgramResourceiv(gbuffer.id(), GL_BUFFER_VARIABLE, objects, 2, objectProperties, 2, nullptr, objectValues);
  CHECK(objectValues[0] == GLint(offsetof(gpu::GpuObject, normalFromLocal)));
  CHECK(objectValues[1] == GLint(sizeof(gpu::GpuObject)));
  CHECK(blockDataSize(gbuffer.id(), "MaterialBlock") == GLint(sizeof(gpu::MaterialBlock)));
  CHECK(memberOffset(gbuffer.id(), "MaterialBlock.factors") == GLint(offsetof(gpu::MaterialBlock, factors)));

  const gl::Program composite = passProgram({"composite.glsl", {"radiance"}, {}}, PassForm::Fragment, false);
  CHECK(blockDataSize(composite.id(), "LightingBlock") == GLint(sizeof(gpu::LightingBlock)));
  CHECK(memberOffset(composite.id(), "LightingBlock.skyIntensity") ==
        GLint(offsetof(gpu::LightingBlock, skyIntensity)));

  const gl::Program blur = passProgram({"ssgi_blur.glsl", {"nearField"}, {}}, PassForm::Compute, false);
  CHECK(blockDataSize(blur.id(), "SsgiBlurBlock") == GLint(sizeof(gpu::SsgiBlurBlock)));
  CHECK(memberOffset(blur.id(), "SsgiBlurBlock.ssgiDownsample") == GLint(offsetof(gpu::SsgiBlurBlock, ssgiDownsample)));

  // The lights are std430 and read through a struct: every member's offset.
  const gl::Program direct = passProgram(
      {"direct_light.glsl", {"towardEye"}, {"HAS_PLANAR_SHADOWS", "HAS_CUBE_SHADOWS"}}, PassForm::Fragment, false);
  CHECK(blockDataSize(direct.id(), "LightingBlock") == GLint(sizeof(gpu::LightingBlock)));
  CHECK(memberOffset(direct.id(), "LightingBlock.pcfRadius") == GLint(offsetof(gpu::LightingBlock, pcfRadius)));
  CHECK(memberOffset(direct.id(), "LightingBlock.shadowMapSize") == GLint(offsetof(gpu::LightingBlock, shadowMapSize)));
  auto lightOffset = [&](const char* member) {
    const GLuint index = glGetProgramResourceIndex(direct.id(), GL_BUFFER_VARIABLE, member);
    REQUIRE(index != GL_INVALID_INDEX);
    const GLenum properties[] = {GL_OFFSET, GL_TOP_LEVEL_ARRAY_STRIDE};
    GLint values[2] = {-1, -1};
    glGetProgramResourceiv(direct.id(), GL_BUFFER_VARIABLE, index, 2, properties, 2, nullptr, values);
    CHECK(values[1] == GLint(sizeof(gpu::GpuLight)));
    return values[0];
  };
  CHECK(lightOffset("LightBuffer.lightList[0].range") == GLint(offsetof(gpu::GpuLight, range)));
  CHECK(lightOffset("LightBuffer.lightList[0].type") == GLint(offsetof(gpu::GpuLight, type)));
  CHECK(lightOffset("LightBuffer.lightList[0].castsShadows") == GLint(offsetof(gpu::GpuLight, castsShadows)));
  CHECK(lightOffset("LightBuffer.lightList[0].shadowLayer") == GLint(offsetof(gpu::GpuLight, shadowLayer)));
  CHECK(lightOffset("LightBuffer.lightList[0].shadowTexelSize") == GLint(offsetof(gpu::GpuLight, shadowTexelSize)));
  CHECK(lightOffset("LightBuffer.lightList[0].shadowViewProjection") ==
        GLint(offsetof(gpu::GpuLight, shadowViewProjection)));
  sharedContext().checkErrors("querying uniform block layouts");
}
}  // namespace headlight
