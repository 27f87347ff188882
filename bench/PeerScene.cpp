#include "PeerScene.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include "facet/Error.h"
#include "support/TestMeshes.h"

namespace facet::bench {

namespace {

[[noreturn]] void usage(const char* program, const std::string& problem) {
  std::fprintf(stderr,
               "%s: %s\nusage: %s --triangles N [--frames F] [--threads T] [--image FILE.ppm]\n"
               "  N = 2·theta² for the vtkSphereSource sphere of resolution theta, theta + 2\n",
               program, problem.c_str(), program);
  std::exit(2);
}

std::int64_t positiveArgument(const char* program, std::string_view name, const char* text) {
  char* end = nullptr;
  const long long value = std::strtoll(text, &end, 10);
  if (end == text || *end != '\0' || value <= 0) {
    usage(program, std::string(name) + " must be a positive integer, not '" + text + "'");
  }
  return value;
}

}  // namespace

PeerOptions parsePeerOptions(int argc, char** argv) {
  PeerOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string_view name = argv[i];
    if (i + 1 >= argc) usage(argv[0], "missing value after " + std::string(name));
    if (name == "--image") {
      options.image = argv[++i];
      continue;
    }
    const std::int64_t value = positiveArgument(argv[0], name, argv[++i]);
    if (name == "--triangles") {
      options.triangles = value;
    } else if (name == "--frames") {
      options.frames = static_cast<int>(value);
    } else if (name == "--threads") {
      options.threads = static_cast<int>(value);
    } else {
      usage(argv[0], "unknown option " + std::string(name));
    }
  }
  return options;
}

glm::mat4 PeerScene::clipFromWorld() const {
  const double aspect = double(kPeerWidth) / kPeerHeight;
  return glm::mat4(clipFromView(camera, aspect) * viewFromWorld(camera));
}

PeerScene makePeerScene(std::int64_t triangles) {
  const int theta = static_cast<int>(std::lround(std::sqrt(triangles / 2.0)));
  if (2 * std::int64_t(theta) * theta != triangles) {
    throw Error("no vtkSphereSource sphere has " + std::to_string(triangles) +
                " triangles: the benches' spheres have 2·theta² (20000, 500000, 2000000, ...)");
  }
  const Mesh sphere = testing::makeUvSphere(theta, theta + 2);
  PeerScene scene;
  scene.xyz.reserve(3 * sphere.points.size());
  for (const glm::dvec3& p : sphere.points) {
    scene.xyz.insert(scene.xyz.end(), {float(p.x), float(p.y), float(p.z)});
  }
  scene.indices.assign(sphere.connectivity.begin(), sphere.connectivity.end());
  scene.camera = testing::fitCamera(sphere);
  scene.light = scene.camera.position;
  return scene;
}

std::size_t coveredPixels(const std::vector<float>& depth) {
  return static_cast<std::size_t>(
      std::count_if(depth.begin(), depth.end(), [](float d) { return d < 1.0f; }));
}

void writePpm(const std::string& path, const std::uint8_t* rgba) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) throw Error("cannot write " + path + ": " + std::strerror(errno));
  std::fprintf(file, "P6\n%d %d\n255\n", kPeerWidth, kPeerHeight);
  for (int y = kPeerHeight - 1; y >= 0; --y) {
    for (int x = 0; x < kPeerWidth; ++x)
      std::fwrite(rgba + 4 * (y * kPeerWidth + x), 1, 3, file);
  }
  if (std::fclose(file) != 0) throw Error("cannot write " + path + ": " + std::strerror(errno));
}

double medianFrameSeconds(int frames, const std::function<void()>& frame) {
  frame();
  std::vector<double> seconds;
  for (int i = 0; i < frames; ++i) {
    const auto start = std::chrono::steady_clock::now();
    frame();
    seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::nth_element(seconds.begin(), seconds.begin() + seconds.size() / 2, seconds.end());
  return seconds[seconds.size() / 2];
}

std::string jsonString(const std::string& text) {
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') quoted += '\\';
    if (static_cast<unsigned char>(c) >= 0x20) quoted += c;
  }
  return quoted + "\"";
}

void printPeerResult(const std::string& peer, const PeerOptions& options, const PeerScene& scene,
                     const std::vector<std::pair<std::string, std::string>>& fields) {
  std::printf(
      "{\"peer\": %s, \"triangles\": %zu, \"points\": %zu, \"width\": %d, \"height\": %d, "
      "\"frames\": %d, \"threads\": %d",
      jsonString(peer).c_str(), scene.triangleCount(), scene.pointCount(), kPeerWidth, kPeerHeight,
      options.frames, options.threads);
  for (const auto& [key, value] : fields) {
    std::printf(", %s: %s", jsonString(key).c_str(), value.c_str());
  }
  std::printf("}\n");
}

}  // namespace facet::bench
