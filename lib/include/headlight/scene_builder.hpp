#pragma once
// Building a Scene in code: the built-in scenes, the tests and any program
// that embeds the library use these, with the generators in shapes.hpp.
// Every function appends to the scene it is given and returns the new
// element's index; nothing is checked beyond what the types say, so the
// caller passes indices that these functions returned for the same scene.
#include <glm/glm.hpp>
#include <string>

#include "headlight/export.hpp"
#include "headlight/scene.hpp"

namespace headlight HEADLIGHT_PUBLIC {

// ---- Elements ------------------------------------------------------------------

// A glTF metallic-roughness material with no textures and no emission.
// baseColor: linear RGB 0..1; roughness: perceptual, 0..1; metallic 0..1.
Material makeMaterial(const glm::vec3& baseColor, float roughness, float metallic = 0.0f, std::string name = {});

// A perspective camera at `eye` looking at `target` with +Y up (eye and
// target apart, the view not along Y); yfov: radians, vertical.
Camera makeLookAtCamera(const glm::vec3& eye, const glm::vec3& target, float yfov, std::string name = {});

// The same placement, orthographic, `halfHeight` world units from the
// centre to the top edge and as much to the side edge.
Camera makeOrthographicCamera(const glm::vec3& eye, const glm::vec3& target, float halfHeight, std::string name = {});

// ---- Placements -----------------------------------------------------------------

glm::mat4 moved(const glm::vec3& offset);
// Turned `degrees` about +Y about its own origin, then moved to `center`.
glm::mat4 rotatedAboutYThenMoved(float degrees, const glm::vec3& center);

// ---- Assembly -------------------------------------------------------------------

int addMaterial(Scene& scene, Material material);    // returns its index in scene.materials
int addGeometry(Scene& scene, Primitive primitive);  // returns its index in scene.primitives

// Places geometry `geometry` (an index from addGeometry) with `material` (an
// index from addMaterial, or -1 for the default material). For the ids
// target each placement is a mesh instance named `name`, and each geometry
// a mesh of one primitive ("geometry <index>").
void addInstance(Scene& scene, int geometry, int material, const glm::mat4& worldFromLocal = glm::mat4(1.0f),
                 std::string name = {});

// Geometry used once: added and placed in one step.
void addInstance(Scene& scene, Primitive primitive, int material, const glm::mat4& worldFromLocal = glm::mat4(1.0f),
                 std::string name = {});

}  // namespace HEADLIGHT_PUBLIC
