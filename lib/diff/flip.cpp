// FLIP (lib/diff/flip.hpp). Every 2-D filter is separable and runs as a
// horizontal then a vertical 1-D pass over float planes, each pass a loop
// over taps outside a loop over pixels so that the compiler vectorizes it.
#include "diff/flip.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace headlight::flip {
namespace {

constexpr double kPi = std::numbers::pi;

// Colour pipeline (HPG 2020, section 4.1).
constexpr float kColorExponent = 0.7f;         // q_c: HyAB distance ^ 0.7
constexpr float kRedistributionBreak = 0.4f;   // p_c: of the largest distance ...
constexpr float kRedistributionValue = 0.95f;  // p_t: ... maps to this
// Feature pipeline (section 4.2).
constexpr float kFeatureExponent = 0.5f;        // q_f
constexpr double kFeatureWidthDegrees = 0.082;  // w: peak to trough of the edge detector
// HDR-FLIP (EGSR 2021, section 4): the reference's brightest luminance at the
// start exposure and its median at the stop exposure tone map to this.
constexpr double kToneTarget = 0.85;

// The contrast sensitivity filters of the three opponent channels, each
// a1 sqrt(pi / b1) exp(-pi^2 x^2 / b1) + a2 sqrt(pi / b2) exp(-pi^2 x^2 / b2)
// with x in degrees (HPG 2020, table 1, after Johnson and Fairchild).
struct CsfChannel {
  double a1, b1, a2, b2;
};
constexpr std::array<CsfChannel, 3> kCsf{{
    {1.0, 0.0047, 0.0, 1e-5},   // achromatic (Y)
    {1.0, 0.0053, 0.0, 1e-5},   // red-green (Cx)
    {34.1, 0.04, 13.5, 0.025},  // blue-yellow (Cz)
}};
constexpr double kCsfLargestB = 0.04;

// Linear sRGB to CIE XYZ, derived from the sRGB primaries and D65's
// chromaticity (x, y) = (0.31271, 0.32902), so that RGB (1, 1, 1) has Y = 1.
constexpr float kRgbToXyz[3][3] = {{0.412386563f, 0.357591491f, 0.180450491f},
                                   {0.212636822f, 0.715182982f, 0.072180196f},
                                   {0.019330620f, 0.119197164f, 0.950372587f}};

struct Matrix3 {
  float m[3][3];
};

Matrix3 inverse(const float (&a)[3][3]) {
  const double det = double(a[0][0]) * (double(a[1][1]) * a[2][2] - double(a[1][2]) * a[2][1]) -
                     double(a[0][1]) * (double(a[1][0]) * a[2][2] - double(a[1][2]) * a[2][0]) +
                     double(a[0][2]) * (double(a[1][0]) * a[2][1] - double(a[1][1]) * a[2][0]);
  Matrix3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      // Cofactor of a[j][i], by cyclic indices.
      const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
      r.m[i][j] = float((double(a[r0][c0]) * a[r1][c1] - double(a[r0][c1]) * a[r1][c0]) / det);
    }
  return r;
}

const Matrix3& xyzToRgb() {
  static const Matrix3 matrix = inverse(kRgbToXyz);
  return matrix;
}

// The reference white: XYZ of linear RGB (1, 1, 1).
struct White {
  float x, y, z;
};
constexpr White kWhite{kRgbToXyz[0][0] + kRgbToXyz[0][1] + kRgbToXyz[0][2],
                       kRgbToXyz[1][0] + kRgbToXyz[1][1] + kRgbToXyz[1][2],
                       kRgbToXyz[2][0] + kRgbToXyz[2][1] + kRgbToXyz[2][2]};

float luminance(const float* rgb) {
  return kRgbToXyz[1][0] * rgb[0] + kRgbToXyz[1][1] * rgb[1] + kRgbToXyz[1][2] * rgb[2];
}

// CIELAB's f(t).
float labCurve(float t) {
  constexpr float kDelta = 6.0f / 29.0f;
  return t > kDelta * kDelta * kDelta ? std::cbrt(t) : t / (3.0f * kDelta * kDelta) + 4.0f / 29.0f;
}

struct Lab {
  float l, a, b;
};

// CIELAB of linear RGB with the Hunt adjustment (colourfulness falls with
// luminance: a and b scaled by L / 100).
Lab huntLab(float r, float g, float b) {
  const float x = (kRgbToXyz[0][0] * r + kRgbToXyz[0][1] * g + kRgbToXyz[0][2] * b) / kWhite.x;
  const float y = (kRgbToXyz[1][0] * r + kRgbToXyz[1][1] * g + kRgbToXyz[1][2] * b) / kWhite.y;
  const float z = (kRgbToXyz[2][0] * r + kRgbToXyz[2][1] * g + kRgbToXyz[2][2] * b) / kWhite.z;
  const float fx = labCurve(x), fy = labCurve(y), fz = labCurve(z);
  const float l = 116.0f * fy - 16.0f;
  return {l, 0.01f * l * 500.0f * (fx - fy), 0.01f * l * 200.0f * (fy - fz)};
}

// HyAB: city-block in lightness, Euclidean in chroma.
float hyab(const Lab& p, const Lab& q) {
  const float da = p.a - q.a, db = p.b - q.b;
  return std::abs(p.l - q.l) + std::sqrt(da * da + db * db);
}

// The largest colour difference, between green and blue, after ^ q_c.
float largestColorDifference() {
  static const float value = std::pow(hyab(huntLab(0, 1, 0), huntLab(0, 0, 1)), kColorExponent);
  return value;
}

float redistribute(float difference) {
  const float cmax = largestColorDifference(), knee = kRedistributionBreak * cmax;
  if (difference < knee) return kRedistributionValue / knee * difference;
  return kRedistributionValue + (difference - knee) / (cmax - knee) * (1.0f - kRedistributionValue);
}

// ---- separable filtering ------------------------------------------------------

using Kernel = std::vector<float>;  // 2r + 1 taps, centre at r

struct Plane {
  int width = 0, height = 0;
  std::vector<float> values;
  Plane() = default;
  Plane(int w, int h) : width(w), height(h), values(std::size_t(w) * std::size_t(h), 0.0f) {}
  float* row(int y) { return values.data() + std::size_t(y) * std::size_t(width); }
  const float* row(int y) const { return values.data() + std::size_t(y) * std::size_t(width); }
};

// Horizontal pass, edge pixels repeated.
Plane filterRows(const Plane& in, const Kernel& kernel) {
  const int r = int(kernel.size() / 2), w = in.width;
  Plane out(w, in.height);
  std::vector<float> padded(std::size_t(w + 2 * r));
  for (int y = 0; y < in.height; ++y) {
    const float* src = in.row(y);
    for (int i = 0; i < w + 2 * r; ++i) padded[std::size_t(i)] = src[std::clamp(i - r, 0, w - 1)];
    float* dst = out.row(y);
    for (std::size_t k = 0; k < kernel.size(); ++k) {
      const float weight = kernel[k];
      const float* shifted = padded.data() + k;
      for (int x = 0; x < w; ++x) dst[x] += weight * shifted[x];
    }
  }
  return out;
}

// Vertical pass, edge rows repeated.
Plane filterColumns(const Plane& in, const Kernel& kernel) {
  const int r = int(kernel.size() / 2), w = in.width, h = in.height;
  Plane out(w, h);
  for (int y = 0; y < h; ++y) {
    float* dst = out.row(y);
    for (std::size_t k = 0; k < kernel.size(); ++k) {
      const float weight = kernel[k];
      const float* src = in.row(std::clamp(y + int(k) - r, 0, h - 1));
      for (int x = 0; x < w; ++x) dst[x] += weight * src[x];
    }
  }
  return out;
}

// The CSF of one channel as at most two separable terms: weight * g(x) g(y)
// with g normalized to sum 1; the weights sum to 1 (the 2-D kernel's sum).
struct CsfTerm {
  float weight;
  Kernel taps;
};
using CsfFilter = std::vector<CsfTerm>;

std::array<CsfFilter, 3> makeCsfFilters(double ppd) {
  // Wide enough for three standard deviations of the widest Gaussian.
  const int radius = int(std::ceil(3.0 * std::sqrt(kCsfLargestB / (2.0 * kPi * kPi)) * ppd));
  std::array<CsfFilter, 3> filters;
  for (std::size_t c = 0; c < 3; ++c) {
    const CsfChannel& p = kCsf[c];
    double total = 0;
    for (const auto& [a, b] : {std::pair{p.a1, p.b1}, std::pair{p.a2, p.b2}}) {
      if (a == 0) continue;
      Kernel taps(std::size_t(2 * radius + 1));
      double sum = 0;
      for (int i = -radius; i <= radius; ++i) {
        const double x = i / ppd;
        sum += taps[std::size_t(i + radius)] = float(std::exp(-kPi * kPi * x * x / b));
      }
      for (float& t : taps) t = float(t / sum);
      // The 2-D term's sum is amplitude * sum^2 (before normalizing g).
      const double weight = a * std::sqrt(kPi / b) * sum * sum;
      total += weight;
      filters[c].push_back({float(weight), std::move(taps)});
    }
    for (CsfTerm& term : filters[c]) term.weight = float(term.weight / total);
  }
  return filters;
}

Plane applyCsf(const Plane& in, const CsfFilter& filter) {
  Plane out(in.width, in.height);
  for (const CsfTerm& term : filter) {
    const Plane blurred = filterColumns(filterRows(in, term.taps), term.taps);
    for (std::size_t i = 0; i < out.values.size(); ++i) out.values[i] += term.weight * blurred.values[i];
  }
  return out;
}

// The feature detectors' 1-D factors: the Gaussian (sum 1) and its first and
// second derivatives (positive taps sum to 1, negative to -1).
struct FeatureKernels {
  Kernel gaussian, edge, point;
};

Kernel balanced(Kernel taps) {
  double positive = 0, negative = 0;
  for (float t : taps) (t > 0 ? positive : negative) += t;
  for (float& t : taps) t = float(t > 0 ? t / positive : t / -negative);
  return taps;
}

FeatureKernels makeFeatureKernels(double ppd) {
  const double sigma = 0.5 * kFeatureWidthDegrees * ppd;
  const int radius = int(std::ceil(3.0 * sigma));
  FeatureKernels k;
  double sum = 0;
  for (int i = -radius; i <= radius; ++i) {
    const double g = std::exp(-double(i) * i / (2.0 * sigma * sigma));
    sum += g;
    k.gaussian.push_back(float(g));
    k.edge.push_back(float(-i * g));
    k.point.push_back(float((double(i) * i / (sigma * sigma) - 1.0) * g));
  }
  for (float& t : k.gaussian) t = float(t / sum);
  k.edge = balanced(std::move(k.edge));
  k.point = balanced(std::move(k.point));
  return k;
}

// Edge and point magnitudes of a luminance plane.
struct Features {
  Plane edge, point;
};

Features detectFeatures(const Plane& y, const FeatureKernels& k) {
  const Plane smoothX = filterRows(y, k.gaussian), edgeX = filterRows(y, k.edge), pointX = filterRows(y, k.point);
  const Plane ex = filterColumns(edgeX, k.gaussian), ey = filterColumns(smoothX, k.edge);
  const Plane px = filterColumns(pointX, k.gaussian), py = filterColumns(smoothX, k.point);
  Features f{Plane(y.width, y.height), Plane(y.width, y.height)};
  for (std::size_t i = 0; i < y.values.size(); ++i) {
    // sqrt, not std::hypot (several times slower; no overflow at these magnitudes).
    f.edge.values[i] = std::sqrt(ex.values[i] * ex.values[i] + ey.values[i] * ey.values[i]);
    f.point.values[i] = std::sqrt(px.values[i] * px.values[i] + py.values[i] * py.values[i]);
  }
  return f;
}

// YCxCz planes of an image in [0, 1] linear RGB (values clamped here), and
// its relative luminance for the feature detectors.
struct Opponent {
  std::array<Plane, 3> ycxcz;
  Plane luminance;
};

template <typename ToLinear>
Opponent toOpponent(const RgbView& image, ToLinear toLinear) {
  Opponent o;
  for (Plane& p : o.ycxcz) p = Plane(image.width, image.height);
  o.luminance = Plane(image.width, image.height);
  const std::size_t count = o.luminance.values.size();
  for (std::size_t i = 0; i < count; ++i) {
    const float* src = image.pixels + i * std::size_t(image.stride);
    float rgb[3];
    // NaN (and what tone mapping makes of inf) counts as black: the caller
    // judges non-finite input itself; here it must not spread through the filters.
    for (int c = 0; c < 3; ++c) {
      const float v = toLinear(src[c]);
      rgb[c] = v > 0 ? std::min(v, 1.0f) : 0.0f;
    }
    const float x = (kRgbToXyz[0][0] * rgb[0] + kRgbToXyz[0][1] * rgb[1] + kRgbToXyz[0][2] * rgb[2]) / kWhite.x;
    const float y = luminance(rgb) / kWhite.y;
    const float z = (kRgbToXyz[2][0] * rgb[0] + kRgbToXyz[2][1] * rgb[1] + kRgbToXyz[2][2] * rgb[2]) / kWhite.z;
    o.ycxcz[0].values[i] = 116.0f * y - 16.0f;
    o.ycxcz[1].values[i] = 500.0f * (x - y);
    o.ycxcz[2].values[i] = 200.0f * (y - z);
    o.luminance.values[i] = y;
  }
  return o;
}

// Filtered YCxCz back to linear RGB in the sRGB gamut, then Hunt-adjusted CIELAB.
Lab filteredLab(const std::array<Plane, 3>& filtered, std::size_t i) {
  const float y = (filtered[0].values[i] + 16.0f) / 116.0f;
  const float x = (filtered[1].values[i] / 500.0f + y) * kWhite.x;
  const float z = (y - filtered[2].values[i] / 200.0f) * kWhite.z;
  const Matrix3& m = xyzToRgb();
  float rgb[3];
  for (int c = 0; c < 3; ++c) rgb[c] = std::clamp(m.m[c][0] * x + m.m[c][1] * y * kWhite.y + m.m[c][2] * z, 0.0f, 1.0f);
  return huntLab(rgb[0], rgb[1], rgb[2]);
}

// The filters for one pixels-per-degree, made once per call.
struct Filters {
  std::array<CsfFilter, 3> csf;
  FeatureKernels features;
  explicit Filters(double ppd) : csf(makeCsfFilters(ppd)), features(makeFeatureKernels(ppd)) {}
};

// LDR-FLIP of two images already in opponent space; writes max(out, flip).
void accumulateFlip(const Opponent& reference, const Opponent& test, const Filters& filters, std::vector<float>& out) {
  std::array<Plane, 3> filteredRef, filteredTest;
  for (std::size_t c = 0; c < 3; ++c) {
    filteredRef[c] = applyCsf(reference.ycxcz[c], filters.csf[c]);
    filteredTest[c] = applyCsf(test.ycxcz[c], filters.csf[c]);
  }
  const Features featRef = detectFeatures(reference.luminance, filters.features);
  const Features featTest = detectFeatures(test.luminance, filters.features);
  const float featureScale = float(1.0 / std::numbers::sqrt2);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const float color =
        redistribute(std::pow(hyab(filteredLab(filteredRef, i), filteredLab(filteredTest, i)), kColorExponent));
    const float edge = std::abs(featRef.edge.values[i] - featTest.edge.values[i]);
    const float point = std::abs(featRef.point.values[i] - featTest.point.values[i]);
    const float feature = std::pow(featureScale * std::max(edge, point), kFeatureExponent);
    out[i] = std::max(out[i], std::pow(color, 1.0f - feature));
  }
}

void checkPair(const RgbView& reference, const RgbView& test) {
  auto describe = [](const RgbView& v) { return std::to_string(v.width) + "x" + std::to_string(v.height); };
  if (reference.width != test.width || reference.height != test.height)
    throw std::invalid_argument("FLIP: images of different sizes (reference " + describe(reference) + ", test " +
                                describe(test) + ")");
  if (reference.width <= 0 || reference.height <= 0 || !reference.pixels || !test.pixels)
    throw std::invalid_argument("FLIP: empty image (" + describe(reference) + ")");
  if (reference.stride < 3 || test.stride < 3)
    throw std::invalid_argument("FLIP: expected at least 3 channels per pixel (RGB), got strides " +
                                std::to_string(reference.stride) + " and " + std::to_string(test.stride));
}

void summarize(FlipResult& result) {
  double sum = 0;
  result.minimum = result.error.empty() ? 0.0f : result.error.front();
  result.maximum = result.minimum;
  for (float e : result.error) {
    sum += e;
    result.minimum = std::min(result.minimum, e);
    result.maximum = std::max(result.maximum, e);
  }
  result.mean = result.error.empty() ? 0.0 : sum / double(result.error.size());
}

FlipResult emptyResult(const RgbView& reference) {
  FlipResult result;
  result.width = reference.width;
  result.height = reference.height;
  result.error.assign(std::size_t(reference.width) * std::size_t(reference.height), 0.0f);
  return result;
}

// The exposure x at which the tone curve reaches `target`: the positive root
// of (k0 - k3 t) x^2 + (k1 - k4 t) x + (k2 - k5 t) = 0 for the curve
// (k0 x^2 + k1 x + k2) / (k3 x^2 + k4 x + k5).
constexpr double kAcesPre = 0.6;  // the pre-exposure folded into the fit's coefficients
constexpr double kAces[6] = {kAcesPre * kAcesPre * 2.51, kAcesPre * 0.03, 0.0,
                             kAcesPre* kAcesPre * 2.43,  kAcesPre * 0.59, 0.14};

double acesInverse(double target) {
  const double a = kAces[0] - kAces[3] * target, b = kAces[1] - kAces[4] * target, c = kAces[2] - kAces[5] * target;
  const double half = 0.5 * b / a;
  return -half + std::sqrt(half * half - c / a);
}

// The median of a non-empty range (reordered): for an even count the upper
// of the two middle values, as the published tool takes it.
float medianOf(std::vector<float>::iterator first, std::vector<float>::iterator last) {
  const auto middle = first + (last - first) / 2;
  std::nth_element(first, middle, last);
  return *middle;
}

// The luminance HDR-FLIP's exposure range is chosen by: BT.709's weights
// rounded to 4 decimals, as the published tool uses (the XYZ row above moves
// cornell's stop exposure by 1e-4).
float exposureLuminance(const float* rgb) { return 0.2126f * rgb[0] + 0.7152f * rgb[1] + 0.0722f * rgb[2]; }

}  // namespace

double pixelsPerDegree(double distanceMetres, double displayWidthMetres, double displayWidthPixels) {
  return distanceMetres * (displayWidthPixels / displayWidthMetres) * (kPi / 180.0);
}

double defaultPixelsPerDegree() { return pixelsPerDegree(0.7, 0.7, 3840.0); }



float acesToneMap(float radiance) {
  const double x = radiance;
  return float((kAces[0] * x * x + kAces[1] * x + kAces[2]) / (kAces[3] * x * x + kAces[4] * x + kAces[5]));
}

FlipResult ldrFlip(const RgbView& reference, const RgbView& test, double ppd) {
  checkPair(reference, test);
  FlipResult result = emptyResult(reference);
  const Filters filters(ppd);
  auto identity = [](float v) { return v; };
  accumulateFlip(toOpponent(reference, identity), toOpponent(test, identity), filters, result.error);
  summarize(result);
  return result;
}

ExposureRange hdrExposureRange(const RgbView& reference) {
  const std::size_t count = std::size_t(reference.width) * std::size_t(reference.height);
  std::vector<float> luminances(count);
  for (std::size_t i = 0; i < count; ++i) {
    const float y = exposureLuminance(reference.pixels + i * std::size_t(reference.stride));
    luminances[i] = std::isfinite(y) ? std::max(y, 0.0f) : 0.0f;  // non-finite: as black, like the images
  }
  ExposureRange range;
  const float brightest = luminances.empty() ? 0.0f : *std::max_element(luminances.begin(), luminances.end());
  if (!(brightest > 0)) return range;  // black (or empty): one exposure pair at 1
  float median = medianOf(luminances.begin(), luminances.end());
  if (!(median > 0)) {
    // More than half black: the median of the lit pixels.
    const auto lit = std::partition(luminances.begin(), luminances.end(), [](float v) { return !(v > 0); });
    median = medianOf(lit, luminances.end());
  }
  const double x = acesInverse(kToneTarget);
  range.start = std::log2(x / brightest);
  range.stop = std::log2(x / median);
  range.count = std::max(2, int(std::ceil(range.stop - range.start)));
  return range;
}

FlipResult hdrFlip(const RgbView& reference, const RgbView& test, double ppd) {
  checkPair(reference, test);
  return hdrFlip(reference, test, hdrExposureRange(reference), ppd);
}

FlipResult hdrFlip(const RgbView& reference, const RgbView& test, const ExposureRange& exposures, double ppd) {
  checkPair(reference, test);
  FlipResult result = emptyResult(reference);
  result.startExposure = exposures.start;
  result.stopExposure = exposures.stop;
  result.exposureCount = std::max(exposures.count, 1);
  const Filters filters(ppd);
  const double step =
      result.exposureCount > 1 ? (exposures.stop - exposures.start) / double(result.exposureCount - 1) : 0.0;
  for (int e = 0; e < result.exposureCount; ++e) {
    const float scale = float(std::exp2(exposures.start + step * e));
    auto toneMapped = [scale](float v) { return acesToneMap(std::max(v, 0.0f) * scale); };
    accumulateFlip(toOpponent(reference, toneMapped), toOpponent(test, toneMapped), filters, result.error);
  }
  summarize(result);
  return result;
}

}  // namespace headlight::flip
