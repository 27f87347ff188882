// A small command-line front end to ImageMetrics.h, for test_ssim_skimage.py:
//
//   facet_image_metrics_tool compare A.png B.png
//       prints {"rmse": ..., "max": ..., "psnr": ..., "ssim": ...} for B against A (every
//       pixel counts as covered: a PNG has no coverage)
//   facet_image_metrics_tool sphere-pair FLAT.png REFERENCE.png
//       writes a flat-shaded tessellated sphere (the rasterizer) and its analytic reference,
//       a real pair of the kind Facet compares

#include <png.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "../support/TestMeshes.h"
#include "../support/TestRender.h"
#include "facet/AnalyticReference.h"
#include "facet/ImageMetrics.h"

namespace {

using facet::FloatImage;

// PNG rows run top to bottom; FloatImage rows bottom to top.
FloatImage readPng(const std::string& path) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str())) {
    throw std::runtime_error(path + ": " + png.message);
  }
  png.format = PNG_FORMAT_RGB;
  std::vector<png_byte> bytes(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, bytes.data(), 0, nullptr)) {
    throw std::runtime_error(path + ": " + png.message);
  }
  FloatImage image(static_cast<int>(png.width), static_cast<int>(png.height));
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const png_byte* p =
          &bytes[3 * (static_cast<std::size_t>(image.height - 1 - y) * image.width + x)];
      image.color[image.indexOf(x, y)] = facet::Color(p[0], p[1], p[2]) / 255.0f;
      image.coverage[image.indexOf(x, y)] = 1.0f;
    }
  }
  return image;
}

void writePng(const std::string& path, const std::vector<facet::Rgba8>& pixels, int width,
              int height) {
  std::vector<png_byte> bytes;
  for (int y = height - 1; y >= 0; --y) {
    for (int x = 0; x < width; ++x) {
      const facet::Rgba8& p = pixels[static_cast<std::size_t>(y) * width + x];
      bytes.insert(bytes.end(), {p.r, p.g, p.b});
    }
  }
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(width);
  png.height = static_cast<png_uint_32>(height);
  png.format = PNG_FORMAT_RGB;
  if (!png_image_write_to_file(&png, path.c_str(), 0, bytes.data(), 0, nullptr)) {
    throw std::runtime_error(path + ": " + png.message);
  }
}

void compare(const std::string& a, const std::string& b) {
  const facet::ImageError error = facet::compareImages(readPng(a), readPng(b));
  // JSON has no infinity; Python's json module reads `Infinity`.
  const std::string psnr = std::isinf(error.psnr) ? "Infinity" : std::to_string(error.psnr);
  std::printf("{\"rmse\": %.17g, \"max\": %.17g, \"psnr\": %s, \"ssim\": %.17g}\n", error.rmse,
              error.maxError, psnr.c_str(), error.ssim.value_or(-2.0));
}

void spherePair(const std::string& flatPath, const std::string& referencePath) {
  constexpr int kWidth = 160, kHeight = 120;
  const facet::Mesh sphere = facet::testing::makeUvSphere(12, 7);
  const facet::Camera camera = facet::testing::fitCamera(sphere, {0.3, -0.2, -1.0});
  facet::LightSet lights;
  lights.lights.push_back(facet::PointLight{{2.0, 3.0, 4.0}});
  const auto flat = facet::testing::renderScene(
      facet::testing::oneMeshScene(sphere.view(), facet::Material{}, lights), camera, kWidth,
      kHeight);
  writePng(flatPath, {flat.framebuffer.color().begin(), flat.framebuffer.color().end()}, kWidth,
           kHeight);
  facet::AnalyticScene scene;
  scene.spheres.push_back({});
  scene.lights = lights;
  const auto reference = facet::renderAnalyticReference(scene, camera, kWidth, kHeight);
  writePng(referencePath, facet::toRgba8(reference.image), kWidth, kHeight);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string command = argc > 1 ? argv[1] : "";
    if (argc == 4 && command == "compare") {
      compare(argv[2], argv[3]);
    } else if (argc == 4 && command == "sphere-pair") {
      spherePair(argv[2], argv[3]);
    } else {
      std::fprintf(stderr, "usage: %s compare A.png B.png | sphere-pair FLAT.png REFERENCE.png\n",
                   argv[0]);
      return 2;
    }
  } catch (const std::exception& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return 1;
  }
  return 0;
}
