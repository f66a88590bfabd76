#pragma once
// Small geometry generators for scenes built in code (the built-in scenes,
// tests, tools that embed the library). Every result is indexed, with unit
// normals, TEXCOORD_0 and bounds; triangles are counter-clockwise seen from
// the side their normals point to, as glTF and GL expect.
#include <glm/glm.hpp>

#include "headlight/export.hpp"
#include "headlight/scene.hpp"

namespace headlight HEADLIGHT_PUBLIC {

// The parallelogram corner, corner+edgeU, corner+edgeU+edgeV, corner+edgeV,
// facing cross(edgeU, edgeV); UV (0,1) at the corner, (1,0) opposite.
Primitive makeQuad(const glm::vec3& corner, const glm::vec3& edgeU, const glm::vec3& edgeV);

// A square through `center` facing `normal` (unit), `halfSize` each way.
Primitive makeSquare(const glm::vec3& center, const glm::vec3& normal, float halfSize);

// A square floor at y = 0 facing +Y, `halfSize` each way from the origin.
Primitive makeFloor(float halfSize);

// An axis-aligned box centred on the origin with outward faces; each face
// has its own four vertices so that the normals stay flat.
Primitive makeBox(const glm::vec3& size);

// A UV sphere: `segments` around, `rings` pole to pole, vertices on the
// sphere (so the polyhedron lies inside it). The seam column is duplicated so
// that texcoords run 0..1; the poles are rings of coincident vertices, whose
// zero-area triangles cost little and keep the code simple.
Primitive makeUvSphere(float radius, int segments, int rings, const glm::vec3& center = glm::vec3(0.0f));

}  // namespace HEADLIGHT_PUBLIC
