#pragma once
// The scene as Embree sees it: one triangle geometry per instance, in world
// space, with what a hit needs to shade itself (geometry id = instance
// index). Masked materials' cut-out texels are holes to every ray.
// alphaMode BLEND instances go into a scene of their own, which only the
// primary rays composite (tracer.cpp): as in the rasteriser, they cast no
// shadow and block no AO, sky or indirect ray.
#include <glm/glm.hpp>

#include <vector>

#include "headlight/scene.hpp"
#include "reference/embree_handles.hpp"

namespace headlight::reference {

struct InstanceShading {
  const Scene* scene = nullptr;          // its images, for masked cut-outs
  const Primitive* primitive = nullptr;  // null for an instance with no triangles
  const Material* material = nullptr;
  glm::mat3 normalFromLocal{1.0f};        // headlight::normalMatrix, as gpu_scene.cpp uses
  const float* worldPositions = nullptr;  // Embree's vertex buffer, xyz per vertex
  float frontSign = 1.0f;                 // glTF: a transform with negative determinant flips the winding
};

struct TracedScene {
  EmbreeDevice device;
  EmbreeScene scene;    // every instance but the blended ones
  EmbreeScene blended;  // the alphaMode BLEND instances (empty scene when none)
  bool hasBlended = false;
  std::vector<InstanceShading> instances;  // indexed by geometry id
};

// True where `instance`'s material is alphaMode MASK and the surface at
// barycentrics (u, v) of `triangle` has alpha below the cutoff: a hole
// (gbuffer.frag's discard). Embree's filter functions skip such hits.
bool cutOut(const InstanceShading& instance, unsigned triangle, float u, float v);

// Flattens `scene` into a committed Embree scene. `threads` > 0 bounds
// Embree's BVH-building threads. The result points into `scene`, which must
// outlive it. Throws Error naming the instance for an out-of-range
// primitive, material, image or vertex index, and for any Embree error.
TracedScene buildScene(const Scene& scene, int threads);

}  // namespace headlight::reference
