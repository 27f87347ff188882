#pragma once

/// @file ImageMetrics.h
/// How far a rendered image is from a reference (Reference.h): the numbers Facet reports as
/// "error". Every difference is in 8-bit units (1 = one step of an 8-bit channel, 1/255).
///
/// - **RMSE**: the root mean square of the channel differences over the pixels covered in
///   either image (coverage > 0): the background both images share does not dilute it.
/// - **Maximum error**: the largest absolute channel difference over those pixels.
/// - **PSNR**: 20·log10(255 / RMSE) dB (+∞ for identical images).
/// - **SSIM**: Wang, Bovik, Sheikh & Simoncelli 2004, "Image quality assessment: from error
///   visibility to structural similarity", on luminance over the whole frame: 11 × 11
///   Gaussian window of σ = 1.5 (scipy's, truncated at 3.5σ), K1 = 0.01, K2 = 0.03,
///   L = 255, population (co)variances, averaged over the pixels whose window lies inside
///   the image — what scikit-image's `structural_similarity(gaussian_weights=True,
///   sigma=1.5, use_sample_covariance=False, data_range=255)` computes (cross-checked by
///   tests/core/test_ssim_skimage.py).
/// - **Silhouette error**: the pixels whose coverage differs, each image's coverage read as
///   "covered" when at least half the pixel is (kCoveredFraction), as a fraction of the
///   pixels covered in either image.
/// - **Interior RMSE**: the RMSE over pixels fully covered in both images, i.e. the shading
///   error without the silhouette's aliasing.
/// - **Error image**: per pixel, the largest absolute channel difference (so its maximum is
///   the maximum error), 0 outside the compared pixels.
///
/// Both images must show the surface over the same background: pixels covered in neither
/// are not compared.

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "facet/FloatImage.h"

namespace facet {

/// A pixel counts as covered for the silhouette error when its coverage is at least this.
/// Why one half: a straight edge through a pixel covers more than half of it exactly when
/// it covers the pixel's center (any line through the center halves the square), so a
/// converged reference thresholded at 1/2 has the silhouette a one-sample-per-pixel
/// rasterizer with exact edges would draw.
inline constexpr float kCoveredFraction = 0.5f;

/// Luminance weights for SSIM: ITU-R BT.709's relative luminance Y = 0.2126 R + 0.7152 G +
/// 0.0722 B. Facet's colors are linear RGB (no transfer curve is applied before the 8-bit
/// output), and BT.709 gives luminance for linear values with sRGB's primaries; Rec. 601's
/// luma weights (0.299, 0.587, 0.114) are meant for gamma-encoded values.
inline constexpr double kLuminanceWeights[3] = {0.2126, 0.7152, 0.0722};

/// SSIM's window: radius int(3.5·σ + 0.5) = 5 for σ = 1.5 (scipy.ndimage's truncation).
inline constexpr int kSsimRadius = 5;
inline constexpr double kSsimSigma = 1.5;

struct ImageError {
  double rmse = 0.0;          ///< 8-bit units, over pixels covered in either image
  double maxError = 0.0;      ///< 8-bit units, over the same pixels
  double psnr = 0.0;          ///< dB; +∞ when rmse is 0
  double interiorRmse = 0.0;  ///< 8-bit units, over pixels fully covered in both
  /// Mean SSIM of the luminance, in [−1, 1]; empty when a side is below 2·kSsimRadius + 1.
  std::optional<double> ssim;
  double silhouetteFraction = 0.0;   ///< silhouettePixels / coveredPixels (0 if none)
  std::size_t comparedPixels = 0;    ///< covered (coverage > 0) in either image
  std::size_t interiorPixels = 0;    ///< fully covered in both
  std::size_t coveredPixels = 0;     ///< covered (≥ kCoveredFraction) in either image
  std::size_t silhouettePixels = 0;  ///< covered in one image but not the other
  /// Per pixel, the largest absolute channel difference in 8-bit units (row 0 at the bottom).
  std::vector<float> errorImage;
};

/// Compares a test image with a reference of the same size. Throws facet::Error naming the
/// sizes when they differ, or the first pixel with a non-finite color or a coverage outside
/// [0, 1]. Symmetric in the two images except for the names.
ImageError compareImages(const FloatImage& reference, const FloatImage& test);

/// 20·log10(255 / rmse) in dB, +∞ for rmse = 0.
double psnrFromRmse(double rmse);

/// BT.709 luminance (kLuminanceWeights) of every pixel, in 8-bit units ([0, 255]).
std::vector<double> luminance(const FloatImage& image);

/// Mean SSIM of two luminance images of width × height pixels (values in [0, 255]), as
/// described above; empty when a side is below 2·kSsimRadius + 1 (no window fits). Throws
/// facet::Error when a span does not hold width × height values.
std::optional<double> structuralSimilarity(std::span<const double> a, std::span<const double> b,
                                           int width, int height);

}  // namespace facet
