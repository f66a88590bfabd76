// headlight diff: OpenImageIO's compare() under idiff's rules, with an error
// metric per target. Flow of diffImages:
//   load A, B as float -> structure checks (size, channel names) ->
//   select channels (B reordered to A's order) -> NaN/Inf counts ->
//   metric images EA, EB with |EA - EB| = the error -> compare() over all
//   channels (pixel counts, max) and per channel -> status -> difference image.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "color/srgb.hpp"
#include "diff/flip.hpp"
#include "headlight/diff.hpp"
#include "headlight/error.hpp"
#include "headlight/limits.hpp"
#include "headlight/output.hpp"
#include "image_io/atomic_image.hpp"
#include "image_io/image_files.hpp"
#include "io/atomic_file.hpp"
#include "scene/address_space.hpp"
#include "io/bounded_read.hpp"

namespace headlight {
namespace {

namespace fs = std::filesystem;
using diffio::checkOk;
using diffio::declaredFloatBytes;
using diffio::openImage;
using diffio::readImage;
using diffio::rgbChannels;
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

std::string percent(double value) { return number(value) + "%"; }

bool isCoverageChannel(std::string_view name) {
  return name == "A" || (name.size() > 2 && name.substr(name.size() - 2) == ".A");
}

std::string mebibytes(double bytes) { return number(bytes / double(1 << 20)) + " MiB"; }

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

// Channel names of `image` that `other` lacks.
std::vector<std::string> missingFrom(const OIIO::ImageSpec& image, const OIIO::ImageSpec& other) {
  std::vector<std::string> missing;
  for (const std::string& name : image.channelnames)
    if (other.channelindex(name) < 0) missing.push_back(name);
  return missing;
}

// Which channels to compare, or a problem (Structural).
std::vector<std::string> selectChannels(const OIIO::ImageSpec& a, const OIIO::ImageSpec& b, const DiffResult& result,
                                        const DiffOptions& options, std::string& problem) {
  if (!options.channels.empty()) {
    for (const std::string& name : options.channels) {
      if (a.channelindex(name) < 0)
        problem = result.a.string() + " has no channel '" + name + "' (it has " + joined(a.channelnames) + ")";
      else if (b.channelindex(name) < 0)
        problem = result.b.string() + " has no channel '" + name + "' (it has " + joined(b.channelnames) + ")";
      if (!problem.empty()) return {};
    }
    return options.channels;
  }
  const std::vector<std::string> onlyA = missingFrom(a, b), onlyB = missingFrom(b, a);
  if (!onlyA.empty() || !onlyB.empty()) {
    problem = "channel names differ: A has [" + joined(a.channelnames) + "], B has [" + joined(b.channelnames) + "]";
    if (!onlyA.empty()) problem += "; only in A: " + joined(onlyA);
    if (!onlyB.empty()) problem += "; only in B: " + joined(onlyB);
    return {};
  }
  return a.channelnames;
}

OIIO::ImageBuf pickChannels(const OIIO::ImageBuf& image, const std::vector<std::string>& names) {
  std::vector<int> order;
  for (const std::string& name : names) order.push_back(image.spec().channelindex(name));
  return OIIO::ImageBufAlgo::channels(image, int(names.size()), order, {}, names);
}

// A one-channel float image named `name` holding `values`.
OIIO::ImageBuf singleChannel(const OIIO::ROI& roi, const std::string& name, const float* values) {
  OIIO::ImageSpec spec(roi.width(), roi.height(), 1, OIIO::TypeDesc::FLOAT);
  spec.x = roi.xbegin;
  spec.y = roi.ybegin;
  spec.channelnames = {name};
  OIIO::ImageBuf out(spec);
  out.set_pixels(out.roi(), OIIO::TypeDesc::FLOAT, values);
  return out;
}

// The angle between A's and B's vectors per pixel, in degrees. A loop, not
// ImageBufAlgo: OIIO has no acos/atan2 op, and acos of a float dot product
// resolves no better than ~0.02 deg near 0 (1 - cos is below float's
// epsilon there), while atan2(|a x b|, a.b) in double stays exact enough for
// the 0.1-degree warn level. Length-independent, so unnormalized input is fine.
OIIO::ImageBuf angleImage(const OIIO::ImageBuf& a, const OIIO::ImageBuf& b, const std::string& name) {
  const OIIO::ROI roi = a.roi();
  const std::size_t count = roi.npixels();
  std::vector<float> va(count * 3), vb(count * 3), angle(count);
  a.get_pixels(roi, OIIO::TypeDesc::FLOAT, va.data());
  b.get_pixels(roi, OIIO::TypeDesc::FLOAT, vb.data());
  for (std::size_t i = 0; i < count; ++i) {
    const double ax = va[3 * i], ay = va[3 * i + 1], az = va[3 * i + 2];
    const double bx = vb[3 * i], by = vb[3 * i + 1], bz = vb[3 * i + 2];
    const bool zeroA = ax == 0 && ay == 0 && az == 0, zeroB = bx == 0 && by == 0 && bz == 0;
    double degrees;
    if (zeroA && zeroB)
      degrees = 0;  // background in both (normal.exr holds 0 there)
    else if (zeroA || zeroB)
      degrees = 180;  // geometry in one only: the largest possible angle
    else {
      const double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
      degrees =
          std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), ax * bx + ay * by + az * bz) * (180.0 / std::numbers::pi);
    }
    angle[i] = float(degrees);  // NaN input stays NaN
  }
  return singleChannel(roi, name, angle.data());
}

std::string prefixOf(const std::string& channel) {
  const auto dot = channel.rfind('.');
  return dot == std::string::npos ? std::string() : channel.substr(0, dot);
}

// The scene size RelativeToScene divides by: A's headlight:far (the view's
// far plane, fitted 1 % beyond the farthest scene point, so the depth extent
// of what the camera sees), else the largest finite |value| of A's
// non-coverage channels (files from other tools), else 1.
void chooseScale(const OIIO::ImageBuf& a, const std::vector<std::string>& channels, DiffResult& result) {
  const float far = a.spec().get_float_attribute("headlight:far", 0.0f);
  if (std::isfinite(far) && far > 0) {
    result.scale = far;
    result.scaleSource = "headlight:far of A";
    return;
  }
  const OIIO::ImageBufAlgo::PixelStats stats = OIIO::ImageBufAlgo::computePixelStats(a);
  double largest = 0;
  for (std::size_t c = 0; c < channels.size() && c < stats.min.size(); ++c) {
    if (isCoverageChannel(channels[c])) continue;
    for (double v : {double(stats.min[c]), double(stats.max[c])})
      if (std::isfinite(v)) largest = std::max(largest, std::abs(v));
  }
  result.scale = largest > 0 ? largest : 1.0;
  result.scaleSource = largest > 0 ? "largest |value| in A (no headlight:far)" : "1 (no headlight:far, A is all zero)";
}

struct MetricImages {
  OIIO::ImageBuf a, b;                    // |a - b| is the error, channel by channel
  std::vector<std::vector<int>> sources;  // per metric channel: indices into the selected channels
};

// FLIP of the R, G, B channels as channel "flip" of EA (EB zero), then the
// other channels (coverage) as they are, compared absolutely. HDR-FLIP takes
// its exposures from A, the reference; LDR-FLIP decodes sRGB first.
// A pair whose HDR-FLIP would need more exposures than DiffOptions::maxFlipExposures.
struct TooManyExposures {
  std::string problem;
};

MetricImages flipImages(const OIIO::ImageBuf& a, const OIIO::ImageBuf& b, const std::vector<std::string>& channels,
                        const std::vector<int>& rgb, bool ldr, int maxExposures, DiffResult& result) {
  namespace iba = OIIO::ImageBufAlgo;
  const OIIO::ROI roi = a.roi();
  const std::size_t count = roi.npixels();
  std::vector<float> rgbA(count * 3), rgbB(count * 3);
  const OIIO::ImageBuf pickedA = iba::channels(a, 3, rgb), pickedB = iba::channels(b, 3, rgb);
  checkOk(pickedA, "channels");
  checkOk(pickedB, "channels");
  pickedA.get_pixels(roi, OIIO::TypeDesc::FLOAT, rgbA.data());
  pickedB.get_pixels(roi, OIIO::TypeDesc::FLOAT, rgbB.data());
  const flip::RgbView viewA{rgbA.data(), roi.width(), roi.height(), 3},
      viewB{rgbB.data(), roi.width(), roi.height(), 3};
  FlipDetails details;
  details.hdr = !ldr;
  details.pixelsPerDegree = flip::defaultPixelsPerDegree();
  flip::FlipResult flipped;
  if (ldr) {
    for (float& v : rgbA) v = srgbToLinear(v);
    for (float& v : rgbB) v = srgbToLinear(v);
    flipped = flip::ldrFlip(viewA, viewB, details.pixelsPerDegree);
  } else {
    const flip::ExposureRange exposures = flip::hdrExposureRange(viewA);
    if (exposures.count > maxExposures) {
      char span[96];
      std::snprintf(span, sizeof span, "exposures 2^%.1f to 2^%.1f", exposures.start, exposures.stop);
      throw TooManyExposures{"HDR-FLIP would evaluate " + std::to_string(exposures.count) +
                             " exposures, one a stop from A's brightest luminance to its median (" + span +
                             "), more than --max-flip-exposures " + std::to_string(maxExposures) +
                             " allows; raise --max-flip-exposures to compare them (each is a whole FLIP of the image)"};
    }
    flipped = flip::hdrFlip(viewA, viewB, exposures, details.pixelsPerDegree);
    details.startExposure = flipped.startExposure;
    details.stopExposure = flipped.stopExposure;
    details.exposureCount = flipped.exposureCount;
  }
  result.flip = details;

  MetricImages m;
  m.sources = {rgb};
  std::vector<int> others;
  for (int c = 0; c < int(channels.size()); ++c)
    if (std::find(rgb.begin(), rgb.end(), c) == rgb.end()) {
      others.push_back(c);
      m.sources.push_back({c});
    }
  const OIIO::ImageBuf flipA = singleChannel(roi, "flip", flipped.error.data());
  const OIIO::ImageBuf flipB = iba::zero(flipA.roi());
  if (others.empty()) {
    m.a = flipA;
    m.b = flipB;
  } else {
    m.a = iba::channel_append(flipA, iba::channels(a, int(others.size()), others));
    m.b = iba::channel_append(flipB, iba::channels(b, int(others.size()), others));
  }
  return m;
}

MetricImages metricImages(const OIIO::ImageBuf& a, const OIIO::ImageBuf& b, const std::vector<std::string>& channels,
                          bool integerPixels, int maxFlipExposures, DiffResult& result) {
  namespace iba = OIIO::ImageBufAlgo;
  MetricImages m;
  const int n = int(channels.size());
  for (int c = 0; c < n; ++c) m.sources.push_back({c});
  switch (result.metric) {
    case DiffMetric::Absolute:
      m.a = a.copy(OIIO::TypeDesc::FLOAT);
      m.b = b.copy(OIIO::TypeDesc::FLOAT);
      break;
    case DiffMetric::RelativeToScene: {
      chooseScale(a, channels, result);
      std::vector<float> factors;
      for (const std::string& name : channels)
        factors.push_back(isCoverageChannel(name) ? 1.0f : float(1.0 / result.scale));
      m.a = iba::mul(a, factors);
      m.b = iba::mul(b, factors);
      break;
    }
    case DiffMetric::RelativeToValue: {
      // a/d - b/d = (a - b)/d with d = max(1, |a|) per pixel and channel.
      const OIIO::ImageBuf denominator = iba::max(iba::abs(a), 1.0f);
      checkOk(denominator, "max");
      m.a = iba::div(a, denominator);
      m.b = iba::div(b, denominator);
      break;
    }
    case DiffMetric::AngleDegrees: {
      const std::string prefix = prefixOf(channels[0]);
      m.a = angleImage(a, b, prefix.empty() ? "angle" : prefix + ".angle");
      m.b = iba::zero(m.a.roi());
      m.sources = {{0, 1, 2}};
      break;
    }
    case DiffMetric::Flip:
      m = flipImages(a, b, channels, rgbChannels(channels), integerPixels, maxFlipExposures, result);
      break;
    case DiffMetric::Mismatch: {
      // B holds 1 where the values differ, A zeros: their difference is the error.
      std::vector<float> va(a.roi().npixels() * std::size_t(n)), vb(va.size());
      a.get_pixels(a.roi(), OIIO::TypeDesc::FLOAT, va.data());
      b.get_pixels(b.roi(), OIIO::TypeDesc::FLOAT, vb.data());
      for (std::size_t i = 0; i < va.size(); ++i) vb[i] = va[i] == vb[i] ? 0.0f : 1.0f;
      OIIO::ImageSpec spec = a.spec();
      spec.set_format(OIIO::TypeDesc::FLOAT);
      m.b = OIIO::ImageBuf(spec);
      m.b.set_pixels(m.b.roi(), OIIO::TypeDesc::FLOAT, vb.data());
      m.a = iba::zero(m.b.roi());
      break;
    }
  }
  checkOk(m.a, "metric (A)");
  checkOk(m.b, "metric (B)");
  return m;
}

std::vector<float> valuesAt(const OIIO::ImageBuf& image, int x, int y, const std::vector<int>& channels) {
  std::vector<float> values;
  for (int c : channels) values.push_back(image.getchannel(x, y, 0, c));
  return values;
}

void buildDifference(const OIIO::ImageBuf& a, const OIIO::ImageBuf& b, const MetricImages& m,
                     const std::vector<std::string>& channels, DiffResult& result) {
  namespace iba = OIIO::ImageBufAlgo;
  const OIIO::ImageBuf raw = iba::absdiff(a, b);
  const OIIO::ImageBuf metricError = iba::absdiff(m.a, m.b);
  checkOk(raw, "absdiff");
  checkOk(metricError, "absdiff");
  const std::size_t count = a.roi().npixels();
  const int rawChannels = int(channels.size()), errorChannels = metricError.nchannels();
  std::vector<float> rawPixels(count * std::size_t(rawChannels)), errorPixels(count * std::size_t(errorChannels));
  raw.get_pixels(raw.roi(), OIIO::TypeDesc::FLOAT, rawPixels.data());
  metricError.get_pixels(metricError.roi(), OIIO::TypeDesc::FLOAT, errorPixels.data());
  ImageF& out = result.difference;
  out.width = result.width;
  out.height = result.height;
  out.channels = channels;
  out.channels.push_back("error");
  out.pixels.resize(count * out.channels.size());
  // Max over channels by hand: ImageBufAlgo::maxchan leaves NaN handling to
  // std::max's argument order, and a NaN must show as the worst error.
  for (std::size_t p = 0; p < count; ++p) {
    float* pixel = &out.pixels[p * out.channels.size()];
    std::copy_n(&rawPixels[p * std::size_t(rawChannels)], rawChannels, pixel);
    float worst = 0;
    for (int c = 0; c < errorChannels; ++c) {
      const float e = errorPixels[p * std::size_t(errorChannels) + std::size_t(c)];
      worst = std::isfinite(e) ? std::max(worst, e) : std::numeric_limits<float>::infinity();
    }
    pixel[rawChannels] = worst;
  }
}

const ChannelDiff* worstMean(const DiffResult& r) {
  const auto worst =
      std::max_element(r.channels.begin(), r.channels.end(),
                       [](const ChannelDiff& a, const ChannelDiff& b) { return a.meanError < b.meanError; });
  return worst == r.channels.end() ? nullptr : &*worst;
}

// idiff's verdict, plus NaN/Inf (which compare() skips when both images
// have one at the same place, and does not count as failing otherwise).
void judge(DiffResult& r) {
  const DiffThresholds& t = r.thresholds;
  const double pixels = double(r.pixelCount);
  auto where = [&] {
    return " at (" + std::to_string(r.maxX) + ", " + std::to_string(r.maxY) + ") in " + r.maxChannel;
  };
  if (r.nonFiniteValues > 0) {
    std::string detail;
    for (const ChannelDiff& c : r.channels)
      if (c.nonFiniteA + c.nonFiniteB > 0)
        detail += (detail.empty() ? "" : ", ") + c.name + ": " + std::to_string(c.nonFiniteA) + " in A, " +
                  std::to_string(c.nonFiniteB) + " in B";
    r.status = DiffStatus::Fail;
    r.problem = std::to_string(r.nonFiniteValues) + " NaN/Inf values (" + detail + ")";
  } else if (double(r.failingPixels) > t.failPercent / 100.0 * pixels) {
    r.status = DiffStatus::Fail;
    r.problem = percent(r.failingPercent) + " of pixels (" + std::to_string(r.failingPixels) + ") have error > fail " +
                number(t.fail) + ", allowed " + percent(t.failPercent) + "; max " + number(r.maxError) + where();
  } else if (r.maxError > t.hardFail) {
    r.status = DiffStatus::Fail;
    r.problem = "max error " + number(r.maxError) + where() + " > hardfail " + number(t.hardFail);
  } else if (const ChannelDiff* worst = worstMean(r); worst && worst->meanError > t.failMean) {
    r.status = DiffStatus::Fail;
    r.problem = "mean error " + number(worst->meanError) + " in " + worst->name + " > failmean " + number(t.failMean) +
                " (the pixels within the allowance differ by too much)";
  } else if (double(r.warningPixels) > t.warnPercent / 100.0 * pixels) {
    r.status = DiffStatus::Warn;
    r.problem = percent(r.warningPercent) + " of pixels (" + std::to_string(r.warningPixels) + ") have error > warn " +
                number(t.warn) + ", allowed " + percent(t.warnPercent) + "; max " + number(r.maxError) + where();
  } else if (r.maxError > t.hardWarn) {
    r.status = DiffStatus::Warn;
    r.problem = "max error " + number(r.maxError) + where() + " > hardwarn " + number(t.hardWarn);
  } else {
    r.status = DiffStatus::Pass;
  }
}

}  // namespace

DiffResult diffImages(const fs::path& a, const fs::path& b, const DiffOptions& options) {
  namespace iba = OIIO::ImageBufAlgo;
  DiffResult result;
  result.a = a;
  result.b = b;
  result.target = options.target.empty() ? a.stem().string() : options.target;
  result.metric = resolveMetric(result.target, options);
  result.thresholds = resolveThresholds(result.target, options);

  std::string problemA, problemB;
  // Both headers first: the declared sizes are checked against the memory
  // limit before either image's pixels are decoded.
  const std::unique_ptr<OIIO::ImageInput> inputA = openImage(a, problemA), inputB = openImage(b, problemB);
  if (inputA && inputB) {
    const double need = 2.0 * (declaredFloatBytes(inputA->spec()) + declaredFloatBytes(inputB->spec()));
    ResourceLimits limits;
    limits.maxMemoryMiB = options.maxMemoryMiB;
    const double allowed = double(maxMemoryBytes(limits));
    if (need > allowed) {
      result.status = DiffStatus::FileError;
      result.problem =
          a.string() + " and " + b.string() + " declare " + std::to_string(inputA->spec().width) + "x" +
          std::to_string(inputA->spec().height) + "x" + std::to_string(inputA->spec().nchannels) + " and " +
          std::to_string(inputB->spec().width) + "x" + std::to_string(inputB->spec().height) + "x" +
          std::to_string(inputB->spec().nchannels) + " values: comparing them needs about " + mebibytes(need) +
          " (both as float, and as much again to compare), more than --max-memory " + "allows (" + mebibytes(allowed) +
          (options.maxMemoryMiB ? ""
                                : ", half of physical memory or of the address-space limit (ulimit -v), the smaller") +
          "); raise --max-memory to compare them";
      return result;
    }
    // A --max-memory set above what the process may map (`ulimit -v`) is no
    // bound: OpenImageIO's failed allocation then ended in an assertion
    // (SIGABRT, issue 32). A quarter of the space is left to the libraries
    // and the decoders.
    if (const std::uint64_t addressSpace = addressSpaceLimitBytes();
        addressSpace > 0 && need > 0.75 * double(addressSpace)) {
      result.status = DiffStatus::FileError;
      result.problem = a.string() + " and " + b.string() + ": comparing them needs about " + mebibytes(need) +
                       ", more than the process's address-space limit (ulimit -v, " +
                       mebibytes(double(addressSpace)) + ") leaves room for; raise ulimit -v";
      return result;
    }
  }
  std::optional<OIIO::ImageBuf> imageA, imageB;
  // Integer pixels (8-bit PNG and the like) are display-encoded values,
  // which the Flip metric decodes as sRGB.
  bool integerA = false, integerB = false;
  if (inputA && inputB) {
    integerA = !inputA->spec().format.is_floating_point();
    integerB = !inputB->spec().format.is_floating_point();
    imageA = readImage(*inputA, a, problemA);
    imageB = readImage(*inputB, b, problemB);
  }
  if (!imageA || !imageB) {
    result.status = DiffStatus::FileError;
    result.problem = problemA + (problemA.empty() || problemB.empty() ? "" : "; ") + problemB;
    return result;
  }
  const OIIO::ImageSpec &specA = imageA->spec(), &specB = imageB->spec();
  result.width = specA.width;
  result.height = specA.height;
  result.pixelCount = std::uint64_t(specA.width) * std::uint64_t(specA.height);
  if (specA.width != specB.width || specA.height != specB.height || specA.x != specB.x || specA.y != specB.y) {
    result.status = DiffStatus::Structural;
    auto window = [](const OIIO::ImageSpec& s) {
      std::string text = std::to_string(s.width) + "x" + std::to_string(s.height);
      if (s.x || s.y) text += " at (" + std::to_string(s.x) + ", " + std::to_string(s.y) + ")";
      return text;
    };
    result.problem = "sizes differ: A is " + window(specA) + ", B is " + window(specB);
    return result;
  }
  std::string problem;
  const std::vector<std::string> channels = selectChannels(specA, specB, result, options, problem);
  if (!problem.empty() || channels.empty()) {
    result.status = DiffStatus::Structural;
    result.problem = problem.empty() ? "no channels to compare" : problem;
    return result;
  }
  const OIIO::ImageBuf selA = pickChannels(*imageA, channels), selB = pickChannels(*imageB, channels);
  checkOk(selA, "channels");
  checkOk(selB, "channels");
  // The angle needs a 3-vector; a --channels subset of a normal target is
  // compared per component instead (the metric in the result says so).
  if (result.metric == DiffMetric::AngleDegrees && channels.size() != 3) result.metric = DiffMetric::Absolute;
  // FLIP needs colour: without R, G and B (a --channels subset) it is absolute too.
  if (result.metric == DiffMetric::Flip && rgbChannels(channels).empty()) result.metric = DiffMetric::Absolute;

  const iba::PixelStats statsA = iba::computePixelStats(selA), statsB = iba::computePixelStats(selB);
  auto nonFinite = [](const iba::PixelStats& s, std::size_t c) {
    return c < s.nancount.size() ? std::uint64_t(s.nancount[c] + s.infcount[c]) : 0;
  };

  MetricImages m;
  try {
    m = metricImages(selA, selB, channels, integerA && integerB, options.maxFlipExposures, result);
  } catch (const TooManyExposures& refused) {
    result.status = DiffStatus::FileError;
    result.problem = a.string() + " and " + b.string() + ": " + refused.problem;
    return result;
  }
  const float fail = float(result.thresholds.fail), warn = float(result.thresholds.warn);
  const iba::CompareResults all = iba::compare(m.a, m.b, fail, warn);
  result.maxError = all.maxerror;
  result.maxX = all.maxx;
  result.maxY = all.maxy;
  result.maxChannel = std::string(m.a.spec().channel_name(all.maxc));
  result.failingPixels = all.nfail;
  result.warningPixels = all.nwarn;
  const double toPercent = result.pixelCount ? 100.0 / double(result.pixelCount) : 0.0;
  result.failingPercent = double(all.nfail) * toPercent;
  result.warningPercent = double(all.nwarn) * toPercent;

  for (int c = 0; c < m.a.nchannels(); ++c) {
    OIIO::ROI roi = m.a.roi();
    roi.chbegin = c;
    roi.chend = c + 1;
    const iba::CompareResults one = iba::compare(m.a, m.b, fail, warn, roi);
    ChannelDiff diff;
    diff.name = std::string(m.a.spec().channel_name(c));
    diff.meanError = one.meanerror;
    diff.rmsError = one.rms_error;
    diff.psnr = one.PSNR;
    diff.maxError = one.maxerror;
    diff.maxX = one.maxx;
    diff.maxY = one.maxy;
    diff.failingPixels = one.nfail;
    diff.warningPixels = one.nwarn;
    diff.failingPercent = double(one.nfail) * toPercent;
    for (int s : m.sources[std::size_t(c)]) {
      diff.sources.push_back(channels[std::size_t(s)]);
      diff.nonFiniteA += nonFinite(statsA, std::size_t(s));
      diff.nonFiniteB += nonFinite(statsB, std::size_t(s));
    }
    diff.valuesA = valuesAt(selA, one.maxx, one.maxy, m.sources[std::size_t(c)]);
    diff.valuesB = valuesAt(selB, one.maxx, one.maxy, m.sources[std::size_t(c)]);
    result.nonFiniteValues += diff.nonFiniteA + diff.nonFiniteB;
    result.channels.push_back(std::move(diff));
  }
  judge(result);
  buildDifference(selA, selB, m, channels, result);
  return result;
}

DirectoryDiff diffDirectories(const fs::path& a, const fs::path& b, const DiffOptions& options) {
  if (!options.target.empty() || !options.channels.empty())
    throw std::invalid_argument("diffDirectories: options.target and options.channels apply to one file, not a folder");
  DirectoryDiff diff;
  diff.a = a;
  diff.b = b;
  std::error_code error;
  for (const fs::path& folder : {a, b}) {
    if (!fs::is_directory(folder, error)) {
      diff.status = DiffStatus::FileError;
      diff.problem += (diff.problem.empty() ? "" : "; ") + folder.string() +
                      (fs::exists(folder, error) ? ": not a folder" : ": no such folder");
    }
  }
  if (diff.status == DiffStatus::FileError) return diff;
  // A set a killed render left half old, half new compares file by file as
  // if whole: refuse it.
  for (const fs::path& folder : {a, b}) {
    const FrameSetCheck check = checkFrameSet(folder);
    if (check.state != FrameSetState::Incomplete) continue;
    diff.status = DiffStatus::FileError;
    diff.incompleteSet = true;
    diff.problem += (diff.problem.empty() ? "" : "; ") + std::string("incomplete output set: ") + check.problem;
  }
  if (diff.incompleteSet) return diff;
  for (const FrameTarget& row : frameTargets()) {
    const std::string_view target = row.name;
    const std::string file = std::string(target) + ".exr";
    const bool inA = fs::exists(a / file, error), inB = fs::exists(b / file, error);
    if (!inA && !inB) continue;
    if (inA && inB) {
      diff.targets.push_back(diffImages(a / file, b / file, options));
      continue;
    }
    DiffResult missing;
    missing.a = a / file;
    missing.b = b / file;
    missing.target = std::string(target);
    missing.metric = row.metric;
    missing.thresholds = resolveThresholds(target, options);
    missing.status = DiffStatus::Structural;
    missing.problem = file + " is in " + (inA ? a : b).string() + " only";
    diff.targets.push_back(std::move(missing));
  }
  if (diff.targets.empty()) {
    diff.status = DiffStatus::FileError;
    diff.problem =
        "no headlight targets (position.exr, normal.exr, ..., lit.exr) in " + a.string() + " or " + b.string();
    return diff;
  }
  for (const DiffResult& target : diff.targets) diff.status = std::max(diff.status, target.status);
  return diff;
}

}  // namespace headlight
