// The core alone, no VTK: a shaded box and sphere lit by two colored point lights over a
// dim ambient (the Sixth 3D shading guide's scene), written to a PNG with libpng.
//
//   build/examples/facet-core-demo [output.png]

#include <png.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "facet/Error.h"
#include "facet/Renderer.h"

namespace {

facet::Mesh box(glm::dvec3 low, glm::dvec3 high)
{
  facet::Mesh mesh;
  for (int i = 0; i < 8; ++i)
  {
    mesh.addPoint({ i & 1 ? high.x : low.x, i & 2 ? high.y : low.y, i & 4 ? high.z : low.z });
  }
  for (auto face : { std::initializer_list<std::int64_t>{ 0, 2, 3, 1 },
         { 4, 5, 7, 6 },
         { 0, 1, 5, 4 },
         { 2, 6, 7, 3 },
         { 0, 4, 6, 2 },
         { 1, 3, 7, 5 } })
  {
    mesh.addPolygon(face);
  }
  return mesh;
}

facet::Mesh sphere(glm::dvec3 center, double radius, int rings, int segments)
{
  facet::Mesh mesh;
  for (int r = 0; r <= rings; ++r)
  {
    const double phi = M_PI * r / rings;
    for (int s = 0; s < segments; ++s)
    {
      const double theta = 2 * M_PI * s / segments;
      mesh.addPoint(center +
        radius *
          glm::dvec3(
            std::sin(phi) * std::cos(theta), std::cos(phi), -std::sin(phi) * std::sin(theta)));
    }
  }
  for (int r = 0; r < rings; ++r)
  {
    for (int s = 0; s < segments; ++s)
    {
      const std::int64_t a = r * segments + s, b = r * segments + (s + 1) % segments;
      mesh.addPolygon({ a, a + segments, b + segments, b }); // quads; the poles' are triangles
    }
  }
  return mesh;
}

bool writePng(const char* path, const facet::Framebuffer& image)
{
  FILE* file = std::fopen(path, "wb");
  if (!file)
    return false;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png)))
  {
    png_destroy_write_struct(&png, &info);
    std::fclose(file);
    return false;
  }
  png_init_io(png, file);
  png_set_IHDR(png,
    info,
    image.width(),
    image.height(),
    8,
    PNG_COLOR_TYPE_RGBA,
    PNG_INTERLACE_NONE,
    PNG_COMPRESSION_TYPE_DEFAULT,
    PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = image.height() - 1; y >= 0; --y)
  { // PNG rows go top down; ours bottom up
    png_write_row(png, reinterpret_cast<png_const_bytep>(&image.color()[image.indexOf(0, y)]));
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return std::fclose(file) == 0;
}

} // namespace

int main(int argc, char** argv)
{
  const char* output = argc > 1 ? argv[1] : "facet-core-demo.png";
  const facet::Mesh cube = box({ -2.6, -1.0, -1.0 }, { -0.6, 1.0, 1.0 });
  const facet::Mesh ball = sphere({ 1.6, 0.0, 0.0 }, 1.1, 24, 48);

  facet::Scene scene;
  facet::Material orange, blue;
  orange.color = { 1.0f, 0.6f, 0.25f };
  blue.color = { 0.45f, 0.6f, 1.0f };
  scene.meshes = { { cube.view(), orange }, { ball.view(), blue } };
  scene.lights.ambient.color = facet::Color(50.0f / 255.0f); // Sixth 3D's dim gray (default)
  const facet::QuadraticAttenuation sixth{ 1.0, 0.0, 0.01 };
  scene.lights.lights = {
    facet::PointLight{ { -3.0, 3.0, 4.0 }, { 1.0f, 0.85f, 0.6f }, 1.4, sixth },  // warm, left
    facet::PointLight{ { 4.0, -1.0, 3.5 }, { 0.35f, 0.55f, 1.0f }, 1.2, sixth }, // cool, right
  };

  facet::Camera camera;
  camera.position = { 1.5, 2.5, 8.0 };
  camera.focalPoint = { 0.0, 0.0, 0.0 };
  camera.viewAngleDegrees = 38.0;
  camera.nearClip = 1.0;
  camera.farClip = 30.0;

  facet::Renderer renderer;
  renderer.setBackground({ 0.08f, 0.08f, 0.1f });
  facet::Framebuffer image(800, 500);
  try
  {
    const facet::RenderStats stats = renderer.render(scene, camera, image);
    std::printf("%s", stats.plan.describe().c_str());
    std::printf(
      "rendered %zu polygons in %.2f ms\n", stats.polygonsDrawn, stats.totalSeconds * 1e3);
  }
  catch (const facet::Error& e)
  {
    std::fprintf(stderr, "facet-core-demo: %s\n", e.what());
    return 1;
  }
  if (!writePng(output, image))
  {
    std::fprintf(stderr, "facet-core-demo: cannot write %s\n", output);
    return 1;
  }
  std::printf("wrote %s\n", output);
  return 0;
}
