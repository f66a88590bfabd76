// The parts of headlight/diff.hpp that read no image: names and the
// thresholds each target is judged by. Outside the image module, so that
// diff's help and option checks do not load OpenImageIO.
#include <algorithm>

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
  }
  return "?";
}

const FrameTarget& targetTolerance(std::string_view target) {
  const FrameTarget* row = findFrameTarget(target);
  return row ? *row : unknownTargetRow();
}

DiffThresholds resolveThresholds(std::string_view target, const DiffOptions& options) {
  DiffThresholds t = targetTolerance(target).thresholds;
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
