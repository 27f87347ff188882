// A peer for `make bench-peers`: Mesa's llvmpipe driven directly through OSMesa, no VTK.
// The bench sphere (PeerScene.h) is uploaded once (vertex and index buffer objects); every
// frame clears, draws it with a core-profile shader that shades flat from the face normal
// (the cross product of the position's screen derivatives, as VTK's flat interpolation
// does, two-sided), and reads RGBA8 and depth back with glReadPixels. llvmpipe rasterizes on
// LP_NUM_THREADS threads (set from --threads); its vertex processing and triangle set-up run
// on the calling thread.
//
//   build/bin/osmesa_peer --triangles 2000000 --frames 10 --threads 2

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "PeerScene.h"

namespace facet::bench {
namespace {

constexpr const char* kVertexShader = R"(#version 330 core
uniform mat4 clipFromWorld;
in vec3 position;
out vec3 worldPosition;
void main() {
  worldPosition = position;
  gl_Position = clipFromWorld * vec4(position, 1.0);
}
)";

constexpr const char* kFragmentShader = R"(#version 330 core
uniform vec3 light;
in vec3 worldPosition;
out vec4 color;
void main() {
  vec3 normal = normalize(cross(dFdx(worldPosition), dFdy(worldPosition)));
  float lit = abs(dot(normal, normalize(light - worldPosition)));  // two-sided
  color = vec4(vec3(lit), 1.0);
}
)";

struct Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

GLuint compile(GLenum stage, const char* source) {
  const GLuint shader = glCreateShader(stage);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    throw Failure(std::string("shader compilation failed: ") + log);
  }
  return shader;
}

GLuint linkProgram() {
  const GLuint program = glCreateProgram();
  glAttachShader(program, compile(GL_VERTEX_SHADER, kVertexShader));
  glAttachShader(program, compile(GL_FRAGMENT_SHADER, kFragmentShader));
  glBindAttribLocation(program, 0, "position");
  glBindFragDataLocation(program, 0, "color");
  glLinkProgram(program);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) throw Failure("shader program failed to link");
  return program;
}

// The mesh in GPU buffers, once: a vertex array (left bound) with the positions and indices.
void upload(const PeerScene& scene) {
  GLuint vertexArray = 0, buffers[2] = {};
  glGenVertexArrays(1, &vertexArray);
  glBindVertexArray(vertexArray);
  glGenBuffers(2, buffers);
  glBindBuffer(GL_ARRAY_BUFFER, buffers[0]);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(scene.xyz.size() * sizeof(float)), scene.xyz.data(),
               GL_STATIC_DRAW);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  glEnableVertexAttribArray(0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffers[1]);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(scene.indices.size() * sizeof(std::uint32_t)),
               scene.indices.data(), GL_STATIC_DRAW);
}

void setUniforms(GLuint program, const PeerScene& scene) {
  glUseProgram(program);
  glUniformMatrix4fv(glGetUniformLocation(program, "clipFromWorld"), 1, GL_FALSE,
                     glm::value_ptr(scene.clipFromWorld()));
  glUniform3f(glGetUniformLocation(program, "light"), float(scene.light.x), float(scene.light.y),
              float(scene.light.z));
}

OSMesaContext createContext() {
  // clang-format off
  const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA,
                            OSMESA_DEPTH_BITS, 24,
                            OSMESA_STENCIL_BITS, 0,
                            OSMESA_ACCUM_BITS, 0,
                            OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION, 3,
                            OSMESA_CONTEXT_MINOR_VERSION, 3,
                            0};
  // clang-format on
  OSMesaContext context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (!context) throw Failure("OSMesaCreateContextAttribs failed (OpenGL 3.3 core, 24-bit depth)");
  return context;
}

int run(const PeerOptions& options) {
  // llvmpipe reads its thread count when the context's screen is created.
  setenv("LP_NUM_THREADS", std::to_string(options.threads).c_str(), 1);
  const PeerScene scene = makePeerScene(options.triangles);
  OSMesaContext context = createContext();
  std::vector<std::uint8_t> window(4u * kPeerWidth * kPeerHeight);
  if (!OSMesaMakeCurrent(context, window.data(), GL_UNSIGNED_BYTE, kPeerWidth, kPeerHeight)) {
    throw Failure("OSMesaMakeCurrent failed");
  }
  const std::string renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));

  const GLuint program = linkProgram();
  upload(scene);
  setUniforms(program, scene);
  glViewport(0, 0, kPeerWidth, kPeerHeight);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);  // every face drawn, as VTK draws them
  glClearColor(0, 0, 0, 1);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);

  std::vector<std::uint8_t> rgba(window.size());
  std::vector<float> depth(std::size_t(kPeerWidth) * kPeerHeight);
  const auto count = static_cast<GLsizei>(scene.indices.size());
  const double seconds = medianFrameSeconds(options.frames, [&] {
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT, nullptr);
    glReadPixels(0, 0, kPeerWidth, kPeerHeight, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    glReadPixels(0, 0, kPeerWidth, kPeerHeight, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  });
  if (const GLenum error = glGetError(); error != GL_NO_ERROR) {
    throw Failure("OpenGL error " + std::to_string(error));
  }
  if (!options.image.empty()) writePpm(options.image, rgba.data());
  printPeerResult("osmesa", options, scene,
                  {{"seconds_per_frame", std::to_string(seconds)},
                   {"pixels_covered", std::to_string(coveredPixels(depth))},
                   {"renderer", jsonString(renderer)}});
  OSMesaDestroyContext(context);
  return 0;
}

}  // namespace
}  // namespace facet::bench

int main(int argc, char** argv) {
  try {
    return facet::bench::run(facet::bench::parsePeerOptions(argc, argv));
  } catch (const std::exception& error) {
    std::fprintf(stderr, "osmesa_peer: %s\n", error.what());
    return 1;
  }
}
