#pragma once
// The settings the frame-plan tests plan with: resolved, every auto value
// set (as Renderer::resolve would), so planFrame can be called without a
// scene or a context; and what those tests ask of a plan.
#include <algorithm>
#include <string>
#include <string_view>

#include "frame/frame_plan.hpp"
#include "headlight/settings.hpp"

namespace headlight::test {

inline RenderSettings resolvedPlanSettings() {
  RenderSettings settings;
  settings.ssgi.radius = 0.5f;
  settings.ssgi.bias = 0.025f;
  settings.ssgi.thickness = 0.1f;
  settings.ssgi.indirectStrength = 1.0f;
  settings.lighting.shadowMapSize = 1024;
  settings.lighting.skyIntensity = 1.0f;
  return settings;
}

// True when the plan skips `work` for a reason that contains `reason`.
inline bool skips(const FramePlan& plan, std::string_view work, std::string_view reason = {}) {
  return std::any_of(plan.skipped.begin(), plan.skipped.end(), [&](const SkippedWork& skipped) {
    return skipped.work == work && skipped.reason.find(reason) != std::string::npos;
  });
}

// The plan's read of the target `name`, or null.
inline const TargetRead* readOf(const FramePlan& plan, std::string_view name) {
  for (const TargetRead& read : plan.reads)
    if (read.target->name == name) return &read;
  return nullptr;
}

}  // namespace headlight::test
