// The error metrics on hand-made images whose answers are known in closed form. SSIM is
// also cross-checked against scikit-image on real image pairs (test_ssim_skimage.py).

#include <algorithm>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "facet/Error.h"
#include "facet/ImageMetrics.h"

namespace facet {
namespace {

// A w × h image, fully covered, with a smooth pattern (so SSIM has structure to compare).
FloatImage patterned(int width, int height) {
  FloatImage image(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float v = 0.5f + 0.3f * std::sin(0.4f * x) * std::cos(0.3f * y);
      image.color[image.indexOf(x, y)] = Color(v, 0.8f * v, 0.3f + 0.5f * v);
      image.coverage[image.indexOf(x, y)] = 1.0f;
    }
  }
  return image;
}

FloatImage offsetBy(FloatImage image, const Color& offset) {
  for (Color& c : image.color)
    c += offset;
  return image;
}

TEST(ImageMetrics, IdenticalImagesHaveNoError) {
  const FloatImage image = patterned(40, 30);
  const ImageError error = compareImages(image, image);
  EXPECT_EQ(error.rmse, 0.0);
  EXPECT_EQ(error.maxError, 0.0);
  EXPECT_EQ(error.psnr, std::numeric_limits<double>::infinity());
  ASSERT_TRUE(error.ssim.has_value());
  EXPECT_NEAR(*error.ssim, 1.0, 1e-12);
  EXPECT_EQ(error.silhouettePixels, 0u);
  EXPECT_EQ(error.comparedPixels, 40u * 30u);
  EXPECT_EQ(error.interiorPixels, 40u * 30u);
}

TEST(ImageMetrics, ConstantOffsetGivesTheOffsetAsRmseAndMaximum) {
  const FloatImage reference = patterned(40, 30);
  for (const double steps : {0.5, 1.0, 3.0, 20.0}) {
    const float delta = static_cast<float>(steps / 255.0);
    const ImageError error = compareImages(reference, offsetBy(reference, Color(delta)));
    // Float storage rounds the offset (colors near 0.5 carry ~3e-8 of absolute error).
    EXPECT_NEAR(error.rmse, steps, 2e-5) << steps;
    EXPECT_NEAR(error.maxError, steps, 2e-5) << steps;
    EXPECT_NEAR(error.interiorRmse, steps, 2e-5) << steps;
    EXPECT_NEAR(error.psnr, 20.0 * std::log10(255.0 / steps), 1e-4) << steps;
  }
}

TEST(ImageMetrics, OneChannelOffsetCountsAsOneThirdOfTheSquares) {
  const FloatImage reference = patterned(20, 20);
  const ImageError error = compareImages(reference, offsetBy(reference, Color(0, 6.0f / 255, 0)));
  EXPECT_NEAR(error.rmse, 6.0 / std::sqrt(3.0), 1e-4);
  EXPECT_NEAR(error.maxError, 6.0, 1e-4);
  EXPECT_NEAR(*std::max_element(error.errorImage.begin(), error.errorImage.end()), 6.0f, 1e-4f);
}

TEST(ImageMetrics, PsnrFormula) {
  EXPECT_NEAR(psnrFromRmse(255.0), 0.0, 1e-12);
  EXPECT_NEAR(psnrFromRmse(25.5), 20.0, 1e-12);
  EXPECT_NEAR(psnrFromRmse(1.0), 48.130803608679102, 1e-12);
  EXPECT_EQ(psnrFromRmse(0.0), std::numeric_limits<double>::infinity());
}

TEST(ImageMetrics, PixelsCoveredInNeitherImageAreNotCompared) {
  FloatImage reference(4, 1), test(4, 1);
  // Pixel 0: covered in both, 10 steps apart in red. Pixel 1: covered only in the test.
  // Pixels 2 and 3: background in both, with different colors (not compared).
  reference.coverage = {1.0f, 0.0f, 0.0f, 0.0f};
  test.coverage = {1.0f, 1.0f, 0.0f, 0.0f};
  reference.color = {Color(0.5f), Color(0.0f), Color(0.0f), Color(0.0f)};
  test.color = {Color(0.5f + 10.0f / 255, 0.5f, 0.5f), Color(20.0f / 255), Color(1.0f),
                Color(0.3f)};
  const ImageError error = compareImages(reference, test);
  EXPECT_EQ(error.comparedPixels, 2u);
  EXPECT_EQ(error.interiorPixels, 1u);
  // (10² + 3·20²) / (2 pixels · 3 channels)
  EXPECT_NEAR(error.rmse, std::sqrt((100.0 + 1200.0) / 6.0), 1e-4);
  EXPECT_NEAR(error.interiorRmse, std::sqrt(100.0 / 3.0), 1e-4);
  EXPECT_NEAR(error.maxError, 20.0, 1e-4);
  EXPECT_NEAR(error.errorImage[0], 10.0f, 1e-4f);
  EXPECT_NEAR(error.errorImage[1], 20.0f, 1e-4f);
  EXPECT_EQ(error.errorImage[2], 0.0f);
  EXPECT_EQ(error.errorImage[3], 0.0f);
}

TEST(ImageMetrics, SilhouetteCountsPixelsCoveredInOneImageAtHalfCoverage) {
  FloatImage reference(5, 1), test(5, 1);
  reference.coverage = {1.0f, 0.6f, 0.4f, 0.5f, 0.0f};
  test.coverage = {1.0f, 0.0f, 0.0f, 1.0f, 1.0f};
  const ImageError error = compareImages(reference, test);
  // Covered (≥ 1/2) in either: pixels 0, 1, 3, 4. Differ: 1 (0.6 vs 0) and 4 (0 vs 1);
  // pixel 2 (0.4 vs 0) is uncovered in both, pixel 3 (exactly 1/2) covered in both.
  EXPECT_EQ(error.coveredPixels, 4u);
  EXPECT_EQ(error.silhouettePixels, 2u);
  EXPECT_DOUBLE_EQ(error.silhouetteFraction, 0.5);
  EXPECT_EQ(error.comparedPixels, 5u);
}

TEST(ImageMetrics, SsimOfConstantImagesIsTheLuminanceTerm) {
  // σ = 0 everywhere, so SSIM = (2ab + C1) / (a² + b² + C1) with C1 = (0.01·255)².
  const int width = 16, height = 13;
  for (const auto& [a, b] : {std::pair(100.0, 100.0), std::pair(100.0, 120.0),
                             std::pair(0.0, 255.0), std::pair(30.0, 5.0)}) {
    const std::vector<double> imageA(width * height, a), imageB(width * height, b);
    const double c1 = 2.55 * 2.55;
    const auto ssim = structuralSimilarity(imageA, imageB, width, height);
    ASSERT_TRUE(ssim.has_value());
    EXPECT_NEAR(*ssim, (2 * a * b + c1) / (a * a + b * b + c1), 1e-12) << a << " vs " << b;
  }
}

TEST(ImageMetrics, SsimOfAnImageAgainstItsNegativeIsNegative) {
  // b = 255 − a: σ_ab = −σ², so the structure term is (C2 − 2σ²)/(2σ² + C2) < 0 wherever the
  // window has contrast, while the luminance term stays positive.
  const FloatImage image = patterned(40, 30);
  std::vector<double> a = luminance(image), b = a;
  for (double& v : b)
    v = 255.0 - v;
  const auto ssim = structuralSimilarity(a, b, 40, 30);
  ASSERT_TRUE(ssim.has_value());
  EXPECT_LT(*ssim, 0.0);
}

TEST(ImageMetrics, SsimFallsAsNoiseGrows) {
  const FloatImage reference = patterned(48, 48);
  double previous = 1.0;
  for (const float amplitude : {1.0f, 4.0f, 16.0f, 64.0f}) {
    FloatImage noisy = reference;
    for (std::size_t i = 0; i < noisy.color.size(); ++i) {
      const float sign = ((i * 2654435761u) >> 7) & 1 ? 1.0f : -1.0f;
      noisy.color[i] += Color(sign * amplitude / 255.0f);
    }
    const double ssim = *compareImages(reference, noisy).ssim;
    EXPECT_LT(ssim, previous) << "noise ±" << amplitude;
    previous = ssim;
  }
}

TEST(ImageMetrics, SsimNeedsAnElevenPixelWindow) {
  EXPECT_FALSE(compareImages(patterned(10, 30), patterned(10, 30)).ssim.has_value());
  EXPECT_FALSE(compareImages(patterned(30, 10), patterned(30, 10)).ssim.has_value());
  EXPECT_TRUE(compareImages(patterned(11, 11), patterned(11, 11)).ssim.has_value());
}

TEST(ImageMetrics, LuminanceUsesBt709Weights) {
  FloatImage image(3, 1);
  image.color = {Color(1, 0, 0), Color(0, 1, 0), Color(0, 0, 1)};
  const std::vector<double> y = luminance(image);
  EXPECT_NEAR(y[0], 0.2126 * 255, 1e-9);
  EXPECT_NEAR(y[1], 0.7152 * 255, 1e-9);
  EXPECT_NEAR(y[2], 0.0722 * 255, 1e-9);
}

TEST(ImageMetrics, FramebufferCoverageComesFromPolygonIds) {
  Framebuffer framebuffer(2, 1);
  framebuffer.color()[0] = {255, 0, 51, 255};
  framebuffer.polygonId()[0] = 7;
  framebuffer.polygonId()[1] = Framebuffer::kBackgroundId;
  const FloatImage image = toFloatImage(framebuffer);
  EXPECT_EQ(image.coverage[0], 1.0f);
  EXPECT_EQ(image.coverage[1], 0.0f);
  EXPECT_FLOAT_EQ(image.color[0].b, 0.2f);
  EXPECT_EQ(toRgba8(image)[0], (Rgba8{255, 0, 51, 255}));
}

TEST(ImageMetrics, BadInputIsNamed) {
  const FloatImage small = patterned(4, 4), large = patterned(5, 4);
  EXPECT_THROW(compareImages(small, large), Error);
  FloatImage broken = small;
  broken.color[3].g = std::nanf("");
  try {
    compareImages(small, broken);
    FAIL() << "a NaN pixel was accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("pixel 3"), std::string::npos) << error.what();
  }
  broken = small;
  broken.coverage[0] = 1.5f;
  EXPECT_THROW(compareImages(small, broken), Error);
  EXPECT_THROW(FloatImage(0, 3), Error);
  const std::vector<double> three(3);
  EXPECT_THROW(structuralSimilarity(three, three, 2, 2), Error);
}

}  // namespace
}  // namespace facet
