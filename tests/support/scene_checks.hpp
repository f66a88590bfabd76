#pragma once
// What the loader tests ask of a loaded scene: the features it names as
// not rendered (Scene::ignored).
#include <algorithm>
#include <string>

#include "headlight/scene.hpp"

namespace headlight::test {

// The scene's note about `feature`, or null when it names none.
inline const IgnoredFeature* findIgnored(const Scene& scene, const std::string& feature) {
  for (const IgnoredFeature& ignored : scene.ignored)
    if (ignored.feature == feature) return &ignored;
  return nullptr;
}

inline bool ignores(const Scene& scene, const std::string& feature) { return findIgnored(scene, feature) != nullptr; }

}  // namespace headlight::test
