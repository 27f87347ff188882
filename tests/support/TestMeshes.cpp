#include "TestMeshes.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <glm/geometric.hpp>

namespace facet::testing {

std::filesystem::path sharedMeshPath(const std::string& fileName) {
  return std::filesystem::path(FACET_SHARED_DATA_DIR) / "meshes" / fileName;
}

Mesh readObj(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path.string());
  Mesh mesh;
  std::string line;
  std::vector<std::int64_t> ids;
  for (int lineNumber = 1; std::getline(in, line); ++lineNumber) {
    std::istringstream fields(line);
    std::string tag;
    fields >> tag;
    if (tag == "v") {
      glm::dvec3 p;
      if (!(fields >> p.x >> p.y >> p.z)) {
        throw std::runtime_error(path.string() + ":" + std::to_string(lineNumber) + ": bad vertex");
      }
      mesh.addPoint(p);
    } else if (tag == "f") {
      ids.clear();
      for (std::string corner; fields >> corner;) {
        const long index = std::stol(corner.substr(0, corner.find('/')));
        ids.push_back(index > 0 ? index - 1 : static_cast<long>(mesh.points.size()) + index);
      }
      if (ids.size() < 3) {
        throw std::runtime_error(path.string() + ":" + std::to_string(lineNumber) + ": bad face");
      }
      mesh.addPolygon(ids);
    }
  }
  return mesh;
}

namespace {

// vtkSphereSource::RequestData for a whole sphere in one piece, step by step in its order and
// arithmetic (radians from degrees, theta = i·Δθ, φ = j·Δφ), so its float points match.
Mesh makeSphereAsVtkSphereSource(int thetaResolution, int phiResolution, double radius,
                                 const glm::dvec3& center) {
  Mesh mesh;
  const std::int64_t north = mesh.addPoint(center + glm::dvec3(0, 0, radius));
  const std::int64_t south = mesh.addPoint(center - glm::dvec3(0, 0, radius));
  constexpr double kRadiansPerDegree = M_PI / 180.0;
  const double deltaTheta = 360.0 * kRadiansPerDegree / thetaResolution;
  const double deltaPhi = 180.0 * kRadiansPerDegree / (phiResolution - 1);
  const int pointsPerMeridian = phiResolution - 2;  // without the poles
  for (int i = 0; i < thetaResolution; ++i) {
    const double theta = i * deltaTheta;
    for (int j = 1; j <= pointsPerMeridian; ++j) {
      const double phi = j * deltaPhi;
      const double ringRadius = radius * std::sin(phi);
      mesh.addPoint(center + glm::dvec3(ringRadius * std::cos(theta), ringRadius * std::sin(theta),
                                        radius * std::cos(phi)));
    }
  }
  const std::int64_t base = std::int64_t{pointsPerMeridian} * thetaResolution;
  // Point j (0 = nearest the north pole) of meridian i, meridians wrapping around.
  const auto at = [&](std::int64_t i, std::int64_t j) -> std::int64_t {
    return (pointsPerMeridian * i % base) + j + 2;
  };
  for (int i = 0; i < thetaResolution; ++i)
    mesh.addPolygon({at(i, 0), at(i + 1, 0), north});
  for (int i = 0; i < thetaResolution; ++i)
    mesh.addPolygon({at(i, pointsPerMeridian - 1), south, at(i + 1, pointsPerMeridian - 1)});
  for (int i = 0; i < thetaResolution; ++i) {
    for (int j = 0; j + 1 < pointsPerMeridian; ++j) {
      mesh.addPolygon({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
      mesh.addPolygon({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
    }
  }
  return mesh;
}

}  // namespace

Mesh makeUvSphere(int thetaResolution, int phiResolution, double radius, const glm::dvec3& center,
                  UvSphereOrder order) {
  if (order == UvSphereOrder::vtkSphereSource)
    return makeSphereAsVtkSphereSource(thetaResolution, phiResolution, radius, center);
  Mesh mesh;
  const std::int64_t north = mesh.addPoint(center + glm::dvec3(0, 0, radius));
  const std::int64_t south = mesh.addPoint(center - glm::dvec3(0, 0, radius));
  const int rings = phiResolution - 2;
  for (int ring = 0; ring < rings; ++ring) {
    const double phi = M_PI * (ring + 1) / (phiResolution - 1);
    for (int i = 0; i < thetaResolution; ++i) {
      const double theta = 2.0 * M_PI * i / thetaResolution;
      mesh.addPoint(center + radius * glm::dvec3(std::sin(phi) * std::cos(theta),
                                                 std::sin(phi) * std::sin(theta), std::cos(phi)));
    }
  }
  const auto at = [&](int ring, int i) -> std::int64_t {
    return 2 + ring * thetaResolution + (i % thetaResolution);
  };
  for (int i = 0; i < thetaResolution; ++i)
    mesh.addPolygon({north, at(0, i), at(0, i + 1)});
  for (int ring = 0; ring + 1 < rings; ++ring) {
    for (int i = 0; i < thetaResolution; ++i) {
      mesh.addPolygon({at(ring, i), at(ring + 1, i), at(ring + 1, i + 1)});
      mesh.addPolygon({at(ring, i), at(ring + 1, i + 1), at(ring, i + 1)});
    }
  }
  for (int i = 0; i < thetaResolution; ++i)
    mesh.addPolygon({south, at(rings - 1, i + 1), at(rings - 1, i)});
  return mesh;
}

Mesh makeFloorGrid(int cells, double extent) {
  Mesh floor;
  for (int j = 0; j <= cells; ++j) {
    for (int i = 0; i <= cells; ++i)
      floor.addPoint({-extent + 2 * extent * i / cells, -extent + 2 * extent * j / cells, 0.0});
  }
  for (int j = 0; j < cells; ++j) {
    for (int i = 0; i < cells; ++i) {
      const std::int64_t a = j * (cells + 1) + i;
      floor.addPolygon({a, a + 1, a + cells + 2});
      floor.addPolygon({a, a + cells + 2, a + cells + 1});
    }
  }
  return floor;
}

Mesh sphereWithBand(int theta) {
  const Mesh sphere = makeUvSphere(theta, theta + 2);
  Mesh banded;
  banded.points = sphere.points;
  const std::size_t polygons = sphere.offsets.size() - 1;
  for (std::size_t p = 0; p < polygons; ++p) {
    const auto begin = static_cast<std::size_t>(sphere.offsets[p]);
    const auto end = static_cast<std::size_t>(sphere.offsets[p + 1]);
    const glm::dvec3 corner = sphere.points[static_cast<std::size_t>(sphere.connectivity[begin])];
    if (std::abs(corner.y - 0.2) < 0.15) continue;  // the band
    banded.connectivity.insert(banded.connectivity.end(), sphere.connectivity.begin() + begin,
                               sphere.connectivity.begin() + end);
    banded.offsets.push_back(static_cast<std::int64_t>(banded.connectivity.size()));
  }
  return banded;
}

Camera nearClippedFloorCamera() {
  Camera camera;
  camera.position = {0.3, 0.1, 1.0};
  camera.focalPoint = {0.3, 1.1, 0.0};
  camera.viewUp = {0.0, 0.0, 1.0};
  camera.viewAngleDegrees = 60.0;
  camera.nearClip = 1.2;
  camera.farClip = 100.0;
  return camera;
}

Mesh makeBox(const glm::dvec3& low, const glm::dvec3& high) {
  Mesh mesh;
  for (int i = 0; i < 8; ++i) {
    mesh.addPoint({(i & 1) ? high.x : low.x, (i & 2) ? high.y : low.y, (i & 4) ? high.z : low.z});
  }
  mesh.addPolygon({0, 2, 3, 1});  // -z
  mesh.addPolygon({4, 5, 7, 6});  // +z
  mesh.addPolygon({0, 1, 5, 4});  // -y
  mesh.addPolygon({2, 6, 7, 3});  // +y
  mesh.addPolygon({0, 4, 6, 2});  // -x
  mesh.addPolygon({1, 3, 7, 5});  // +x
  return mesh;
}

Camera fitCamera(const Mesh& mesh, const glm::dvec3& direction, double viewAngleDegrees) {
  glm::dvec3 low(INFINITY), high(-INFINITY);
  for (const glm::dvec3& p : mesh.points) {
    low = glm::min(low, p);
    high = glm::max(high, p);
  }
  const glm::dvec3 center = 0.5 * (low + high);
  const double radius = 0.5 * glm::length(high - low);
  const double distance = radius / std::sin(viewAngleDegrees * M_PI / 360.0);
  Camera camera;
  camera.focalPoint = center;
  camera.position = center - distance * glm::normalize(direction);
  camera.viewUp =
      std::abs(glm::normalize(direction).y) > 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(0, 1, 0);
  camera.viewAngleDegrees = viewAngleDegrees;
  camera.nearClip = std::max(distance - 1.01 * radius, 1e-3 * distance);
  camera.farClip = distance + 1.01 * radius;
  return camera;
}

Mesh makeStackedSquares(int layers, int cells, bool frontToBack) {
  Mesh mesh;
  for (int i = 0; i < layers; ++i) {
    const double z = -0.1 * (frontToBack ? i : layers - 1 - i);
    const auto first = static_cast<std::int64_t>(mesh.points.size());
    for (int y = 0; y <= cells; ++y) {
      for (int x = 0; x <= cells; ++x)
        mesh.addPoint({-1.0 + 2.0 * x / cells, -1.0 + 2.0 * y / cells, z});
    }
    const auto at = [&](int x, int y) { return first + y * (cells + 1) + x; };
    for (int y = 0; y < cells; ++y) {
      for (int x = 0; x < cells; ++x)
        mesh.addPolygon({at(x, y), at(x + 1, y), at(x + 1, y + 1), at(x, y + 1)});
    }
  }
  return mesh;
}

Camera pixelCamera(int width, int height) {
  Camera camera;
  camera.parallelProjection = true;
  camera.parallelScale = 0.5 * height;
  camera.focalPoint = {0.5 * width, 0.5 * height, 0.0};
  camera.position = {0.5 * width, 0.5 * height, 10.0};
  camera.nearClip = 1.0;
  camera.farClip = 100.0;
  return camera;
}

}  // namespace facet::testing
