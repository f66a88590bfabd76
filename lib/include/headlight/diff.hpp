#pragma once
// Image comparison for regression suites (`headlight diff`), following
// OpenImageIO idiff's semantics. A pixel *fails* when its error exceeds the
// fail threshold; the comparison FAILS when more than failPercent % of the
// pixels fail or any error exceeds hardFail; it WARNS likewise with warn,
// warnPercent and hardWarn; otherwise it PASSES. A NaN or Inf in either image
// always FAILS. The numbers come from OIIO::ImageBufAlgo::compare.
//
// What an "error" is depends on the target (the file stem: position, normal,
// ..., lit), because data targets need different units: see DiffMetric and
// targetTolerances(), which also holds each target's default thresholds and
// why. docs/DIFF.md has the table and the exit codes.
//
// Roles: A is the reference (the golden), B the image under test. A's
// metadata gives the scene scale and A's values the relative denominators.
//
// File problems (missing, unreadable) and structural mismatches (size,
// channel names) are statuses in the result, not exceptions: a regression
// suite wants one verdict per target. Only writeDiffImages throws (IoError).
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "headlight/export.hpp"
#include "headlight/frame.hpp"
#include "headlight/targets.hpp"

namespace headlight HEADLIGHT_PUBLIC {

// Ordered by severity: the worst of several results is the largest. The
// values are the CLI's exit codes (5 is the CLI's usage error).
enum class DiffStatus {
  Pass = 0,
  Warn = 1,
  Fail = 2,
  Structural = 3,  // different size, channel names, or a target in one folder only
  FileError = 4,   // missing or unreadable file or folder
};

std::string_view statusName(DiffStatus status);  // "pass", "warn", "fail", "structural", "file-error"
inline int exitCode(DiffStatus status) { return int(status); }
inline constexpr int kDiffExitUsage = 5;
// Folder mode: a folder's frame.json says its set is incomplete (a killed
// render) or a file differs from what the set wrote; nothing is compared.
inline constexpr int kDiffExitIncompleteSet = 6;

std::string_view metricName(DiffMetric metric);  // "absolute", "relative-to-scene", ..., "flip"
// Every metric's name, in DiffMetric order (the CLI's --metric choices).
std::span<const std::string_view> metricNames();

// The frame-target table's row for `target` (headlight/targets.hpp): its
// metric, thresholds and reason; previewTargetRow() for "preview",
// unknownTargetRow() for any other name.
const FrameTarget& targetTolerance(std::string_view target);
// The first row of the table (frame targets, then preview) judged by
// `metric`, or nullptr (none is): where thresholds in its units come from
// when a metric is chosen explicitly.
const FrameTarget* firstRowWithMetric(DiffMetric metric);

struct DiffOptions {
  // Each set value replaces the target's default (the CLI's --fail, ...).
  std::optional<double> fail, failPercent, hardFail, failMean, warn, warnPercent, hardWarn;
  // Channels to compare, by name, in this order; empty = every channel. A
  // name missing from either image is a Structural result.
  std::vector<std::string> channels;
  // Table row to use; empty = A's file stem.
  std::string target;
  // The metric instead of the row's (the CLI's --metric). When it differs
  // from the row's, the default thresholds are those of
  // firstRowWithMetric(*metric) (flip: lit's), since the row's are in other units.
  std::optional<DiffMetric> metric;
  // MiB the decoded images may take (A and B as float, and as much again
  // for the comparison), checked on their declared sizes before any pixel
  // is decoded; nullopt: half of physical memory or of RLIMIT_AS, the smaller (the CLI's --max-memory).
  std::optional<std::int64_t> maxMemoryMiB;
  // HDR-FLIP evaluates FLIP once per exposure, one a stop from A's brightest
  // pixel to its median: a pair needing more is refused before the first (a
  // denormal median under a pixel at FLT_MAX asked for 277, ~95 s of work).
  // The CLI's --max-flip-exposures.
  int maxFlipExposures = 64;
};

// The metric the row of `target` and the options give.
DiffMetric resolveMetric(std::string_view target, const DiffOptions& options);
// The target's defaults (see DiffOptions::metric) with the options' overrides applied.
DiffThresholds resolveThresholds(std::string_view target, const DiffOptions& options);

// The Flip metric's details: which FLIP and its viewing conditions.
struct FlipDetails {
  bool hdr = true;             // HDR-FLIP (float images); false: LDR-FLIP of sRGB-decoded integer images
  double pixelsPerDegree = 0;  // 67.02: 0.7 m from a 0.7 m wide 3840-px display
  double startExposure = 0, stopExposure = 0;  // HDR-FLIP: from A (the reference)
  int exposureCount = 0;
};

struct ChannelDiff {
  std::string name;                  // compared channel: "R", "position.X", or "normal.angle"
  std::vector<std::string> sources;  // the input channels it is computed from
  double meanError = 0;              // mean error over all pixels, in the metric's units
  double rmsError = 0;
  double psnr = std::numeric_limits<double>::infinity();  // 20 log10(1 / rms), as OIIO computes it
  double maxError = 0;                                    // +inf where only one image is NaN/Inf there (OIIO's rule)
  int maxX = 0, maxY = 0;                                 // pixel of maxError
  std::vector<float> valuesA, valuesB;                    // `sources` of A and B at (maxX, maxY)
  std::uint64_t failingPixels = 0;                        // error > fail
  std::uint64_t warningPixels = 0;                        // error > warn (failing pixels included)
  double failingPercent = 0;                              // of all pixels
  std::uint64_t nonFiniteA = 0, nonFiniteB = 0;           // NaN or Inf values in the sources
};

struct DiffResult {
  DiffStatus status = DiffStatus::Pass;
  std::string problem;  // one line saying why the status is not Pass; empty on Pass
  std::filesystem::path a, b;
  std::string target;  // table row used
  DiffMetric metric = DiffMetric::Absolute;
  DiffThresholds thresholds;        // as used
  double scale = 1;                 // RelativeToScene only: the divisor
  std::string scaleSource;          // e.g. "headlight:far of A"
  std::optional<FlipDetails> flip;  // Flip only, once computed
  int width = 0, height = 0;
  std::uint64_t pixelCount = 0;
  std::vector<ChannelDiff> channels;  // empty for Structural and FileError
  // Over all channels (a pixel counts once however many channels fail).
  double maxError = 0;
  int maxX = 0, maxY = 0;
  std::string maxChannel;
  std::uint64_t failingPixels = 0, warningPixels = 0;
  double failingPercent = 0, warningPercent = 0;
  std::uint64_t nonFiniteValues = 0;  // in A and B together
  // Per compared input channel |a - b| under its own name, then "error": the
  // per-pixel maximum of the metric's error over channels (+inf where an
  // input is NaN/Inf). Empty for Structural and FileError.
  ImageF difference;
};

// Compares image B against reference A. Never throws for file or structure
// problems: they are the result's status and problem.
DiffResult diffImages(const std::filesystem::path& a, const std::filesystem::path& b, const DiffOptions& options = {});

struct DirectoryDiff {
  DiffStatus status = DiffStatus::Pass;  // the worst of `targets`, or FileError (see problem)
  std::string problem;                   // set when a folder is missing or holds no target
  // Set (and status FileError, targets empty) when A or B holds an
  // incomplete frame set (checkFrameSet, headlight/output.hpp): exit code
  // kDiffExitIncompleteSet.
  bool incompleteSet = false;
  std::filesystem::path a, b;
  std::vector<DiffResult> targets;  // in frameTargets() order; a target in one folder only is Structural
};

// Compares every <target>.exr of frameTargets() present in either folder.
// options.target and options.channels must be empty (each file uses its own
// row); throws std::invalid_argument otherwise.
DirectoryDiff diffDirectories(const std::filesystem::path& a, const std::filesystem::path& b,
                              const DiffOptions& options = {});

// Writes result.difference as a float EXR at `exrPath` and a heatmap PNG
// beside it (same name, .png): the "error" channel through the inferno
// colour map, scaled so the fail threshold is mid-scale (fail = 0: the
// largest error is full scale); for the Flip metric, the FLIP map as FLIP's
// papers show it, 0..1 through magma, and beside it <stem>_a.png and
// <stem>_b.png, A and B as FLIP saw them (8-bit sRGB; float images ACES tone
// mapped at the middle of the HDR-FLIP exposures), for reports. Both written atomically (temporary name in
// the same folder, then rename). Returns the paths written. Throws IoError when
// writing fails, Error when the result has no difference image.
std::vector<std::filesystem::path> writeDiffImages(const DiffResult& result, const std::filesystem::path& exrPath);

}  // namespace HEADLIGHT_PUBLIC
