#pragma once
// Dimensions of the built-in failure-case scenes that the stability suite
// measures against (tests/stability): one definition for the scene and the
// measurement.

namespace headlight::builtin {

// builtin:slats: thin vertical slats in front of a wall facing +Z at z = 0.
struct SlatLayout {
  static constexpr int kCount = 9;
  static constexpr float kFirstX = -0.8f, kSpacing = 0.2f;              // slat centres
  static constexpr float kWidth = 0.04f, kHeight = 2.0f, kGap = 0.12f;  // gap: wall to slat centre
};

// builtin:depth-step: a sphere well in front of a wall.
struct DepthStepLayout {
  static constexpr float kWallZ = -3.0f, kSphereRadius = 0.6f, kSphereZ = -1.0f;
};

}  // namespace headlight::builtin
