#pragma once

// Phase 0: what is known about each mesh before a render reads it. An unversioned mesh
// (MeshView::version 0) is validated every render; a versioned one once per version, and
// measured then: its bounding box, the boxes of its blocks of polygons that the rules test
// the lights and the view against, and its polygons' unit normals (the shade phase's).

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "Box.h"
#include "Frame.h"
#include "MeshAccess.h"
#include "PhaseRunner.h"
#include "facet/Scene.h"

namespace facet::detail {

// Polygons per block: the unit the view culls (Rule::GeometryOutsideView). 1024 keeps a
// block's box tight on a dense mesh while 2M polygons make only ~2000 boxes to test.
inline constexpr int kBlockBits = 10;
inline constexpr std::size_t kPolygonsPerBlock = std::size_t{1} << kBlockBits;

// The range of point ids a block's polygons use.
struct PointSpan {
  std::size_t first = SIZE_MAX, last = 0;
};

// Polygons per back-face block (BackFacingBlocks.h): a sixteenth of a view-culling block, so
// that the normals of a block of a sphere's triangles span a cone narrow enough to lie wholly
// behind the eye's side of the sphere: in vtkSphereSource's order (meridian by meridian) a
// block of 64 at 500k is an 11° sliver of a meridian, where 256 was 45° and skipped a third
// as many back faces (bench/core-frame-issue11.md, section 37). The test per block shares its
// view-culling block's clip-space bounds (ParentClipBounds), so 31k blocks at 2M cost less
// than the back faces they save.
inline constexpr int kBackBlockBits = 6;
inline constexpr std::size_t kPolygonsPerBackBlock = std::size_t{1} << kBackBlockBits;
static_assert(kBackBlockBits <= kBlockBits);

// The needed-point flags (Transform.h) a back-face block's two point spans fall in, what the
// frame's markNeededPoints reads for every block in view and not skipped: [first, end) flag
// ranges, empty when first == end. A block with scattered flags (BackBlock) has lowFirst
// kReadWholeBackBlock and its flags at [highFirst, highEnd) of MeshFacts::scatteredPointFlags;
// so has every block of a mesh with more flags (or corners) than 32 bits count, whose spans are
// in MeshFacts::wideBackSpans instead.
struct BackPointFlags {
  std::uint32_t lowFirst = 0, lowEnd = 0, highFirst = 0, highEnd = 0;
};
inline constexpr std::uint32_t kReadWholeBackBlock = UINT32_MAX;

// What a back-face block's polygons share, as measureBackBlock finds it (BackFacingBlocks.h
// says how a frame uses it): the cone their normals lie in and the smallest size and worst
// shape among them. `skippable` is false unless every polygon is a triangle of finite points
// with an area and a shape whose normal the measurement can trust (BackFacingBlocks.cpp,
// measureBackBlock). Not kept: a mesh version keeps its compact form (BackBlockTest,
// BackPointFlags), 60 bytes where this is ~200 (bench/core-frame-issue11.md, section 44).
struct BackBlock {
  Box box;  // the points its triangles use
  // Their ids, as two spans split at the middle of their range (the second may be empty): a
  // block of a mesh ordered in strips (a quarter ring of a UV sphere's two rings) uses two
  // runs far apart, and the points between them may be used only by blocks that are skipped
  // (ViewCulling.cpp).
  PointSpan lowPoints, highPoints;
  // When those spans cover far more points than the block's polygons use (a cap of a sphere
  // listed meridian by meridian, vtkSphereSource's: one point per meridian, the whole mesh
  // apart), the needed-point flags (Transform.h) its points fall in, ascending, each once:
  // marking them frees the points between (ViewCulling.cpp). Empty otherwise.
  std::vector<std::uint32_t> scatteredPointFlags;
  glm::dvec3 axis{0.0};
  double angle = 0.0;                     // half-angle of the cone, widened for rounding
  double cosAngle = 0.0, sinAngle = 1.0;  // its cosine and sine
  double minDoubleArea = 0.0;             // the smallest |(p1 − p0) × (p2 − p0)|, rounded down
  double maxPerimeterPerDoubleArea = 0.0;  // the largest perimeter / doubled area, rounded up
  bool skippable = false;
  bool allFinite = true;  // every point its polygons use is finite
};

// The grid a view-culling block's back-face blocks' boxes are kept on (BackBlockTest): a box
// corner q (0..65535 per coordinate) is origin + q·step, the view-culling block's box low
// corner and a 65535th of its size (a little more, so that 65535 reaches its high corner).
struct BackBlockFrame {
  glm::dvec3 origin{0.0};
  glm::dvec3 step{0.0};
};

// What every frame's cull reads of a back-face block (BackFaceTest), per mesh version: its
// box in steps of its view-culling block's BackBlockFrame, rounded outward; its cone in float,
// the axis rounded and the angle widened to cover that, the cosine rounded down (and divided
// by the rounded axis' length) and the sine up; the ball radius (of the stepped box, about
// its centre) and the sizes rounded outward too. 44 bytes, where the measured BackBlock is
// ~200; at 2M polygons 31k blocks are tested a frame. A test that passes on these passes on
// the exact record's proof (BackFacingBlocks.h, "The compact record"). cosAngle is 0 unless
// the block is skippable and its box could be stepped (a skippable block's is at least
// cos 1.5): the pre-test rejects it then, and the back pass's hidden blocks take none of it.
struct BackBlockTest {
  std::uint16_t low[3] = {0, 0, 0}, high[3] = {0, 0, 0};
  float axis[3] = {0.0F, 0.0F, 0.0F};
  float cosAngle = 0.0F, sinAngle = 1.0F;
  float ballRadius = 0.0F;
  float minDoubleArea = 0.0F, maxPerimeterPerDoubleArea = 0.0F;
};
static_assert(sizeof(BackBlockTest) == 44);

// What makes two MeshViews the same arrays (MeshView::version's promise).
struct MeshIdentity {
  const void* points = nullptr;
  const void* offsets = nullptr;
  const void* connectivity = nullptr;
  PointArray::Type pointType = PointArray::Type::Float64;
  PolygonArray::Type indexType = PolygonArray::Type::Int64;
  std::size_t pointCount = 0, polygonCount = 0, connectivitySize = 0;
  std::uint64_t version = 0;

  static MeshIdentity of(const MeshView& mesh);
  friend bool operator==(const MeshIdentity&, const MeshIdentity&) = default;
};

struct MeshFacts {
  MeshIdentity identity;
  bool measured = false;                  // validated, with boxes and blocks, for this identity
  bool bounded = false;                   // `bounds` and `allFinite` hold for this render
  Box bounds;                             // its finite points
  bool allFinite = true;                  // no point has a NaN or infinite coordinate
  std::vector<Box> blocks;                // per block: the finite points its polygons use
  std::vector<std::uint8_t> blockFinite;  // per block: every point it uses is finite
  // Per polygon, for a measured mesh: its unit normal rounded to float (FaceNormal.h).
  std::vector<glm::vec3> faceNormals;
  // A measured mesh whose every polygon is a triangle (offsets[p] = 3p): its corners can be
  // read without the offsets (MeshAccess.h, Triangles).
  bool allTriangles = false;
  // Per back-face block (kPolygonsPerBackBlock polygons): its compact record and point flags,
  // what the frame reads of it; per view-culling block the grid its back-face blocks' boxes
  // are kept on.
  std::vector<BackBlockTest> backTests;
  std::vector<BackPointFlags> backPointFlags;
  std::vector<BackBlockFrame> backFrames;
  // The scattered blocks' flags, in block order (BackPointFlags).
  std::vector<std::uint32_t> scatteredPointFlags;
  // Two per back-face block, only for a mesh with more needed-point flags or corners than 32
  // bits count (BackPointFlags).
  std::vector<PointSpan> wideBackSpans;

  std::size_t backBlockCount() const { return backTests.size(); }
  const BackBlockFrame& backFrameOf(std::size_t block) const {
    return backFrames[block >> (kBlockBits - kBackBlockBits)];
  }
  // Every polygon of the block is a triangle and its record can skip it (BackBlockTest).
  bool backSkippable(std::size_t block) const { return backTests[block].cosAngle > 0.0F; }
};

// The box of a mesh's finite points (for a plan made ahead of a render).
Box boundsOf(const MeshView& mesh);

class MeshCache {
 public:
  // Validates every mesh not known already (throws facet::Error for the first problem, in
  // polygon order, whatever the thread count), and measures the new versions. `bounds`:
  // the bounds of unversioned meshes are wanted too. False when the progress callback asked
  // to stop.
  bool update(PhaseRunner& runner, const Scene& scene, bool bounds);
  const MeshFacts& operator[](std::size_t mesh) const { return facts_[mesh]; }
  // Forgets every mesh (their next render validates them again).
  void clear() { facts_.clear(); }

 private:
  bool validate(PhaseRunner& runner, const Scene& scene);
  bool measure(PhaseRunner& runner, const Scene& scene);
  std::size_t planMeasurement(const Scene& scene);
  void collectBounds(std::size_t pointTasks);
  void collectTriangles(std::size_t pointTasks);
  void collectScatteredFlags(std::size_t pointTasks);

  std::vector<MeshFacts> facts_;
  std::vector<std::uint8_t> checking_, measuring_, bounding_;  // per mesh, this render
  std::vector<MeshRange> ranges_;
  std::vector<std::optional<MeshProblem>> problems_;
  std::vector<Box> rangeBounds_;
  std::vector<std::uint8_t> rangeFinite_;
  std::vector<std::uint8_t> rangeTriangles_;  // per block task: its polygons are all triangles
  std::vector<std::vector<std::uint32_t>> rangeScattered_;  // per block task (measureBlock)
};

}  // namespace facet::detail
