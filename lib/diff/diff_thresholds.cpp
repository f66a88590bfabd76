// The parts of headlight/diff.hpp that read no image: names and the
// thresholds each target is judged by. Outside the image module, so that
// diff's help and option checks do not load OpenImageIO.
#include <algorithm>
#include <vector>

#include "headlight/diff.hpp"

namespace headlight {

std::string_view statusName(DiffStatus status) {
  switch (status) {
    case DiffStatus::Pass:
      return "pass";
    case DiffStatus::Warn:
      return "warn";
    case DiffStatus::Fail:
      return "fail";
    case DiffStatus::Structural:
      return "structural";
    case DiffStatus::FileError:
      return "file-error";
  }
  return "?";
}

std::string_view metricName(DiffMetric metric) {
  switch (metric) {
    case DiffMetric::Absolute:
      return "absolute";
    case DiffMetric::RelativeToScene:
      return "relative-to-scene";
    case DiffMetric::RelativeToValue:
      return "relative-to-value";
    case DiffMetric::AngleDegrees:
      return "angle-degrees";
    case DiffMetric::Flip:
      return "flip";
    case DiffMetric::Mismatch:
      return "mismatch";
  }
  return "?";
}

std::span<const std::string_view> metricNames() {
  static const std::vector<std::string_view> names = [] {
    std::vector<std::string_view> list;
    for (DiffMetric metric : {DiffMetric::Absolute, DiffMetric::RelativeToScene, DiffMetric::RelativeToValue,
                              DiffMetric::AngleDegrees, DiffMetric::Flip, DiffMetric::Mismatch})
      list.push_back(metricName(metric));
    return list;
  }();
  return names;
}

const FrameTarget& targetTolerance(std::string_view target) {
  if (target == previewTargetRow().name) return previewTargetRow();
  const FrameTarget* row = findFrameTarget(target);
  return row ? *row : unknownTargetRow();
}

const FrameTarget* firstRowWithMetric(DiffMetric metric) {
  for (const FrameTarget& row : frameTargets())
    if (row.metric == metric) return &row;
  return previewTargetRow().metric == metric ? &previewTargetRow() : nullptr;
}

DiffMetric resolveMetric(std::string_view target, const DiffOptions& options) {
  return options.metric.value_or(targetTolerance(target).metric);
}

DiffThresholds resolveThresholds(std::string_view target, const DiffOptions& options) {
  const FrameTarget& row = targetTolerance(target);
  const FrameTarget* unitsRow =
      options.metric && *options.metric != row.metric ? firstRowWithMetric(*options.metric) : &row;
  DiffThresholds t = (unitsRow ? *unitsRow : row).thresholds;
  // A mean bound below a per-pixel bound the caller chose would overrule it
  // (every pixel within --fail, the mean above): an explicit --fail raises it.
  if (options.fail) t.failMean = std::max(t.failMean, *options.fail);
  if (options.fail) t.fail = *options.fail;
  if (options.failPercent) t.failPercent = *options.failPercent;
  if (options.hardFail) t.hardFail = *options.hardFail;
  if (options.failMean) t.failMean = *options.failMean;
  if (options.warn) t.warn = *options.warn;
  if (options.warnPercent) t.warnPercent = *options.warnPercent;
  if (options.hardWarn) t.hardWarn = *options.hardWarn;
  return t;
}

}  // namespace headlight
