#include "facet/ImageMetrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include <glm/geometric.hpp>

#include "Validate.h"

namespace facet {
namespace {

constexpr int kSsimTaps = 2 * kSsimRadius + 1;
using SsimKernel = std::array<double, kSsimTaps>;

// scipy.ndimage's Gaussian: exp(−x²/2σ²) at integer offsets, normalized to sum 1.
SsimKernel ssimKernel() {
  SsimKernel kernel{};
  double sum = 0.0;
  for (int i = 0; i < kSsimTaps; ++i) {
    const double x = i - kSsimRadius;
    kernel[i] = std::exp(-0.5 * x * x / (kSsimSigma * kSsimSigma));
    sum += kernel[i];
  }
  for (double& w : kernel)
    w /= sum;
  return kernel;
}

// Local weighted moments of two images: means, second moments and the cross moment.
struct Moments {
  double a = 0.0, b = 0.0, aa = 0.0, bb = 0.0, ab = 0.0;
};

// The horizontal pass over one row, for the columns whose window fits inside it.
void filterRow(const double* a, const double* b, int width, const SsimKernel& kernel,
               Moments* out) {
  for (int x = 0; x + kSsimTaps <= width; ++x) {
    Moments m;
    for (int i = 0; i < kSsimTaps; ++i) {
      const double w = kernel[i], va = a[x + i], vb = b[x + i];
      m.a += w * va;
      m.b += w * vb;
      m.aa += w * va * va;
      m.bb += w * vb * vb;
      m.ab += w * va * vb;
    }
    out[x] = m;
  }
}

// Wang et al. 2004, eq. 13, with population (co)variances from the weighted moments.
double ssimOf(const Moments& m) {
  constexpr double c1 = (0.01 * 255.0) * (0.01 * 255.0);
  constexpr double c2 = (0.03 * 255.0) * (0.03 * 255.0);
  const double varianceA = m.aa - m.a * m.a, varianceB = m.bb - m.b * m.b;
  const double covariance = m.ab - m.a * m.b;
  return (2.0 * m.a * m.b + c1) * (2.0 * covariance + c2) /
         ((m.a * m.a + m.b * m.b + c1) * (varianceA + varianceB + c2));
}

// The vertical pass for one output row, from the kSsimTaps filtered rows around it, summed.
double ssimRowSum(const std::vector<std::vector<Moments>>& ring, int centerRow,
                  const SsimKernel& kernel) {
  double sum = 0.0;
  const std::size_t columns = ring[0].size();
  for (std::size_t x = 0; x < columns; ++x) {
    Moments m;
    for (int i = 0; i < kSsimTaps; ++i) {
      const Moments& h = ring[(centerRow - kSsimRadius + i) % kSsimTaps][x];
      m.a += kernel[i] * h.a;
      m.b += kernel[i] * h.b;
      m.aa += kernel[i] * h.aa;
      m.bb += kernel[i] * h.bb;
      m.ab += kernel[i] * h.ab;
    }
    sum += ssimOf(m);
  }
  return sum;
}

void requireSameSize(const FloatImage& reference, const FloatImage& test) {
  const auto size = [](const FloatImage& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height);
  };
  if (reference.width != test.width || reference.height != test.height) {
    detail::fail("compareImages", "got a reference of " + size(reference) +
                                      " pixels and a test image of " + size(test));
  }
  if (reference.color.size() != reference.pixelCount() || test.color.size() != test.pixelCount() ||
      reference.coverage.size() != reference.pixelCount() ||
      test.coverage.size() != test.pixelCount()) {
    detail::fail("compareImages",
                 "got an image whose color or coverage size is not " + size(reference));
  }
}

// A NaN would poison every sum silently: name the first one instead.
void requireFinitePixels(const FloatImage& image, const char* name) {
  for (std::size_t i = 0; i < image.pixelCount(); ++i) {
    const auto pixelName = [&] { return std::string(name) + " pixel " + std::to_string(i); };
    detail::requireFinite(glm::dvec3(image.color[i]), pixelName);
    detail::requireInRange(image.coverage[i], 0.0, 1.0, [&] { return pixelName() + " coverage"; });
  }
}

// Running sums over the compared pixels.
struct ErrorSums {
  double squared = 0.0, interiorSquared = 0.0;
  std::size_t compared = 0, interior = 0, covered = 0, silhouette = 0;
  double max = 0.0;
};

// Adds one pixel; returns its error-image value.
float addPixel(const FloatImage& reference, const FloatImage& test, std::size_t i,
               ErrorSums& sums) {
  const float coverageR = reference.coverage[i], coverageT = test.coverage[i];
  const bool coveredR = coverageR >= kCoveredFraction, coveredT = coverageT >= kCoveredFraction;
  sums.covered += coveredR || coveredT;
  sums.silhouette += coveredR != coveredT;
  if (!(coverageR > 0.0f || coverageT > 0.0f)) return 0.0f;
  const glm::dvec3 difference =
      255.0 * (glm::dvec3(test.color[i]) - glm::dvec3(reference.color[i]));
  const double squared = glm::dot(difference, difference);
  const double largest =
      std::max({std::abs(difference.x), std::abs(difference.y), std::abs(difference.z)});
  ++sums.compared;
  sums.squared += squared;
  sums.max = std::max(sums.max, largest);
  if (coverageR == 1.0f && coverageT == 1.0f) {
    ++sums.interior;
    sums.interiorSquared += squared;
  }
  return static_cast<float>(largest);
}

double rootMeanSquare(double sumOfSquaredChannels, std::size_t pixels) {
  return pixels == 0 ? 0.0 : std::sqrt(sumOfSquaredChannels / (3.0 * pixels));
}

}  // namespace

double psnrFromRmse(double rmse) {
  if (rmse == 0.0) return std::numeric_limits<double>::infinity();
  return 20.0 * std::log10(255.0 / rmse);
}

std::vector<double> luminance(const FloatImage& image) {
  std::vector<double> y(image.color.size());
  for (std::size_t i = 0; i < y.size(); ++i) {
    const Color& c = image.color[i];
    y[i] = 255.0 *
           (kLuminanceWeights[0] * c.r + kLuminanceWeights[1] * c.g + kLuminanceWeights[2] * c.b);
  }
  return y;
}

std::optional<double> structuralSimilarity(std::span<const double> a, std::span<const double> b,
                                           int width, int height) {
  const std::size_t pixels = static_cast<std::size_t>(std::max(width, 0)) * std::max(height, 0);
  if (a.size() != pixels || b.size() != pixels) {
    detail::fail("structuralSimilarity", "got " + std::to_string(a.size()) + " and " +
                                             std::to_string(b.size()) + " values for " +
                                             std::to_string(width) + "x" + std::to_string(height) +
                                             " pixels");
  }
  if (width < kSsimTaps || height < kSsimTaps) return std::nullopt;
  const SsimKernel kernel = ssimKernel();
  // The horizontal pass of the last kSsimTaps rows, reused as the window slides down.
  std::vector<std::vector<Moments>> ring(kSsimTaps, std::vector<Moments>(width - kSsimTaps + 1));
  const auto filterInto = [&](int row) {
    filterRow(&a[static_cast<std::size_t>(row) * width], &b[static_cast<std::size_t>(row) * width],
              width, kernel, ring[row % kSsimTaps].data());
  };
  for (int row = 0; row + 1 < kSsimTaps; ++row)
    filterInto(row);
  double sum = 0.0;
  for (int center = kSsimRadius; center + kSsimRadius < height; ++center) {
    filterInto(center + kSsimRadius);
    sum += ssimRowSum(ring, center, kernel);
  }
  const double windows = static_cast<double>(width - kSsimTaps + 1) * (height - kSsimTaps + 1);
  return sum / windows;
}

ImageError compareImages(const FloatImage& reference, const FloatImage& test) {
  requireSameSize(reference, test);
  requireFinitePixels(reference, "compareImages reference");
  requireFinitePixels(test, "compareImages test image");
  ImageError error;
  error.errorImage.assign(reference.pixelCount(), 0.0f);
  ErrorSums sums;
  for (std::size_t i = 0; i < reference.pixelCount(); ++i)
    error.errorImage[i] = addPixel(reference, test, i, sums);
  error.rmse = rootMeanSquare(sums.squared, sums.compared);
  error.interiorRmse = rootMeanSquare(sums.interiorSquared, sums.interior);
  error.maxError = sums.max;
  error.psnr = psnrFromRmse(error.rmse);
  error.ssim = structuralSimilarity(luminance(reference), luminance(test), reference.width,
                                    reference.height);
  error.comparedPixels = sums.compared;
  error.interiorPixels = sums.interior;
  error.coveredPixels = sums.covered;
  error.silhouettePixels = sums.silhouette;
  error.silhouetteFraction =
      sums.covered == 0 ? 0.0 : static_cast<double>(sums.silhouette) / sums.covered;
  return error;
}

}  // namespace facet
