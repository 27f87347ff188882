#include "BackFacingBlocks.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <glm/geometric.hpp>

#include "Assert.h"
#include "FaceNormal.h"
#include "Transform.h"
#include "facet/Conventions.h"
#include "facet/PolygonNormal.h"

namespace facet::detail {
namespace {

thread_local ScopedBackBlockSettings::Settings settingsOnThisThread;

constexpr double kUnitRoundoff = 0x1p-53;
// Largest perimeter² / doubled area (1/sin of the smallest angle, within a factor; the
// perimeter bounded as in addTriangle) whose normal is trusted: the cross product's rounding turns
// its direction by at most ~6 unit roundoffs times this (the widening below allows 1e-14 per unit,
// 10× more).
constexpr double kMaxShape = 1e6;
// The widest cone kept (a cost cut-off: a wider block faces away from few viewpoints; the
// angle test in finish() is what the proof needs).
constexpr double kSmallestCosine = 0.05;
// The coordinates' rounding before snapping must stay below this (step 4).
constexpr double kLargestRounding = 0x1p-11;
constexpr double kSnapDelta = 1.0 + 2.0 * kLargestRounding;  // Δ
constexpr double kSlack = 1e-6;

}  // namespace

namespace {

// One back-face block's measurement, polygon by polygon.
class BackBlockMeasure {
 public:
  void addPoint(std::size_t id, const glm::dvec3& point) {
    points_.first = std::min(points_.first, id);
    points_.last = std::max(points_.last, id);
    if (detail::isFinite(point)) {  // qualified: see MeshCache.cpp's boundPoints
      block_.box.add(point);
    } else {
      block_.allFinite = trusted_ = false;
    }
  }
  // A triangle whose cross product triangleCross found plain (its normal trusted so far;
  // its squared sizes neither overflow nor underflow). Squares only, no square roots: the
  // perimeter² is bounded by 3(|ab|² + |ac|² + |bc|²) (Cauchy–Schwarz), exact for an
  // equilateral triangle and 1.5 % over for a right isosceles one (an L1 bound of the
  // perimeter, up to √3 over, cost the 500k sphere its far blocks).
  void addTriangle(const TriangleCross& triangle, const glm::dvec3& unitNormal) {
    const glm::dvec3 bc = triangle.ac - triangle.ab;
    const double perimeterSquared =
        3.0 * (triangle.abSquared + triangle.acSquared + glm::dot(bc, bc));
    const double ratioSquared = perimeterSquared / triangle.lengthSquared;  // (perimeter/2a)²
    const double shapeSquared = ratioSquared * perimeterSquared;            // (perimeter²/2a)²
    if (!(shapeSquared <= kMaxShape * kMaxShape)) {
      trusted_ = false;
      return;
    }
    FACET_ASSERT(count_ < kPolygonsPerBackBlock);  // a block is at most that many polygons
    normals_[count_++] = unitNormal;
    sum_ += unitNormal;
    minAreaSquared_ = std::min(minAreaSquared_, triangle.lengthSquared);
    maxRatioSquared_ = std::max(maxRatioSquared_, ratioSquared);
    maxShapeSquared_ = std::max(maxShapeSquared_, shapeSquared);
  }
  // Any other polygon: its block is never skipped.
  void addOther() { trusted_ = false; }
  BackBlock finish();
  // The ids its polygons use.
  const PointSpan& points() const { return points_; }

 private:
  BackBlock block_;
  PointSpan points_;
  glm::dvec3 normals_[kPolygonsPerBackBlock];
  std::size_t count_ = 0;
  glm::dvec3 sum_{0.0};
  double minAreaSquared_ = std::numeric_limits<double>::infinity();
  double maxRatioSquared_ = 0.0, maxShapeSquared_ = 0.0;
  bool trusted_ = true;
};

BackBlock BackBlockMeasure::finish() {
  const double length = glm::length(sum_);
  if (!trusted_ || !(length > 0.0) || !std::isfinite(length)) return block_;
  const glm::dvec3 axis = sum_ / length;
  double minCosine = 1.0;
  for (std::size_t i = 0; i < count_; ++i)
    minCosine = std::min(minCosine, glm::dot(normals_[i], axis));
  if (!(minCosine >= kSmallestCosine)) return block_;
  // acos near 1 turns a rounding of 1e-16 into ~3e-8 rad: 1e-7 covers it; 1e-14 per unit of
  // shape covers the normals' own rounding.
  const double angle = std::acos(minCosine) + 1e-7 + 1e-14 * std::sqrt(maxShapeSquared_);
  if (!(angle < 1.5)) return block_;
  block_.axis = axis;
  block_.angle = angle;
  block_.cosAngle = std::cos(angle);
  block_.sinAngle = std::sin(angle);
  FACET_ASSERT(block_.cosAngle > 0.0);  // mayFaceAway's mark of a skippable block (testOf)
  block_.minDoubleArea = std::sqrt(minAreaSquared_) * (1.0 - 1e-8);
  block_.maxPerimeterPerDoubleArea = std::sqrt(maxRatioSquared_) * (1.0 + 1e-8);
  block_.skippable = true;
  return block_;
}

// The block's point ids as two spans, split at the middle of their range (MeshCache.h): its
// ids read again, from the caches (cheaper than keeping them in the first pass, measured).
void splitPointSpan(const MeshView& mesh, std::size_t begin, std::size_t end, const PointSpan& all,
                    BackBlock& block) {
  block.lowPoints = all;
  if (all.first > all.last) return;
  const std::size_t middle = all.first + (all.last - all.first) / 2;
  std::size_t lowLast = all.first, highFirst = SIZE_MAX;
  withTypedMesh(mesh, [&](auto, auto polygons) {
    for (std::size_t p = begin; p < end; ++p) {
      for (std::size_t k = 0, n = polygons.size(p); k < n; ++k) {
        const std::size_t id = polygons.pointId(p, k);
        lowLast = std::max(lowLast, id <= middle ? id : all.first);
        highFirst = std::min(highFirst, id <= middle ? SIZE_MAX : id);
      }
    }
  });
  block.lowPoints.last = lowLast;
  if (highFirst <= all.last) block.highPoints = {highFirst, all.last};
}

// A block's spans are scattered when they hold more than this many points per point its
// polygons' corners name: a block of a strip's two rings holds about 1, a sphere's cap listed
// meridian by meridian one per meridian, hundreds.
constexpr std::size_t kScatteredPointsPerCorner = 8;

std::size_t pointsIn(const PointSpan& span) {
  return span.first > span.last ? 0 : span.last - span.first + 1;
}

// The needed-point flags of a scattered block's points (MeshCache.h), when they are fewer
// than the flags its spans cover.
void listScatteredPointFlags(const MeshView& mesh, std::size_t begin, std::size_t end,
                             BackBlock& block) {
  const std::size_t corners = withTypedMesh(mesh, [&](auto, auto polygons) -> std::size_t {
    return polygons.begin(end) - polygons.begin(begin);
  });
  const std::size_t spanned = pointsIn(block.lowPoints) + pointsIn(block.highPoints);
  const std::size_t flagCount = (mesh.points.count + kPointsPerNeededFlag - 1) >> kNeededPointBits;
  if (spanned <= kScatteredPointsPerCorner * corners ||
      flagCount > std::numeric_limits<std::uint32_t>::max()) {
    return;
  }
  std::vector<std::uint32_t>& flags = block.scatteredPointFlags;
  flags.reserve(corners);
  withTypedMesh(mesh, [&](auto, auto polygons) {
    for (std::size_t p = begin; p < end; ++p) {
      for (std::size_t k = 0, n = polygons.size(p); k < n; ++k)
        flags.push_back(static_cast<std::uint32_t>(polygons.pointId(p, k) >> kNeededPointBits));
    }
  });
  std::sort(flags.begin(), flags.end());
  flags.erase(std::unique(flags.begin(), flags.end()), flags.end());
  flags.shrink_to_fit();
}

}  // namespace

BackBlock measureBackBlock(const MeshView& mesh, std::size_t begin, std::size_t end,
                           glm::vec3* faceNormals) {
  BackBlockMeasure measure;
  withTypedMesh(mesh, [&](auto points, auto polygons) {
    for (std::size_t p = begin; p < end; ++p) {
      const std::size_t n = polygons.size(p);
      glm::dvec3 corners[3];
      for (std::size_t k = 0; k < n; ++k) {
        const std::size_t id = polygons.pointId(p, k);
        const glm::dvec3 point = points[id];
        measure.addPoint(id, point);
        if (k < 3) corners[k] = point;
      }
      const auto vertexAt = [&](std::size_t k) -> glm::dvec3 {
        return points[polygons.pointId(p, k)];
      };
      if (n == 3) {
        const TriangleCross triangle = triangleCross(corners[0], corners[1], corners[2]);
        if (triangle.plain) {
          // triangleNormal's own result (FaceNormal.h rounds it the same way).
          const glm::dvec3 unitNormal = triangle.unitNormal();
          measure.addTriangle(triangle, unitNormal);
          if (faceNormals) faceNormals[p] = glm::vec3(unitNormal);
          continue;
        }
      }
      measure.addOther();
      if (faceNormals) faceNormals[p] = faceNormalOf(n, vertexAt);
    }
  });
  BackBlock block = measure.finish();
  splitPointSpan(mesh, begin, end, measure.points(), block);
  listScatteredPointFlags(mesh, begin, end, block);
  return block;
}

namespace {

constexpr double kLastStep = 65535.0;

// Corner q of the grid along one coordinate: the one expression the measurement checks and
// the frame decodes by (BackFacingBlocks.cpp is compiled without fused multiply-adds).
double stepped(double origin, double step, std::uint16_t q) {
  return origin + static_cast<double>(q) * step;
}

// The largest grid corner at most `low` (down) or the smallest at least `high` (up); false
// when there is none (the box far from the origin against its size, or not finite).
bool stepDown(double low, double origin, double step, std::uint16_t& q) {
  double guess = step > 0.0 ? std::floor((low - origin) / step) : 0.0;
  if (!(guess >= 0.0)) guess = 0.0;
  if (!(guess <= kLastStep)) guess = kLastStep;
  q = static_cast<std::uint16_t>(guess);
  for (int tries = 0; tries < 4 && q > 0 && !(stepped(origin, step, q) <= low); ++tries)
    --q;
  if (!(stepped(origin, step, q) <= low)) q = 0;
  return stepped(origin, step, q) <= low;
}
bool stepUp(double high, double origin, double step, std::uint16_t& q) {
  double guess = step > 0.0 ? std::ceil((high - origin) / step) : 0.0;
  if (!(guess >= 0.0)) guess = 0.0;
  if (!(guess <= kLastStep)) guess = kLastStep;
  q = static_cast<std::uint16_t>(guess);
  for (int tries = 0; tries < 4 && q < kLastStep && !(stepped(origin, step, q) >= high); ++tries)
    ++q;
  if (!(stepped(origin, step, q) >= high)) q = static_cast<std::uint16_t>(kLastStep);
  return stepped(origin, step, q) >= high;
}

// x rounded to a float toward −infinity (down) or +infinity (up).
float floatDown(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) > x) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}
float floatUp(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

glm::dvec3 lowOf(const BackBlockTest& block, const BackBlockFrame& frame) {
  return {stepped(frame.origin.x, frame.step.x, block.low[0]),
          stepped(frame.origin.y, frame.step.y, block.low[1]),
          stepped(frame.origin.z, frame.step.z, block.low[2])};
}
glm::dvec3 highOf(const BackBlockTest& block, const BackBlockFrame& frame) {
  return {stepped(frame.origin.x, frame.step.x, block.high[0]),
          stepped(frame.origin.y, frame.step.y, block.high[1]),
          stepped(frame.origin.z, frame.step.z, block.high[2])};
}
glm::dvec3 centerOf(const glm::dvec3& low, const glm::dvec3& high) {
  return 0.5 * low + 0.5 * high;
}
// The centre of a compact record's ball: the stepped box's centre, within rounding, at half the
// decoding's cost (the record's radius is measured from this point).
glm::dvec3 ballCenterOf(const BackBlockTest& block, const BackBlockFrame& frame) {
  const auto at = [&](int k) {
    return frame.origin[k] +
           static_cast<double>(int{block.low[k]} + int{block.high[k]}) * (0.5 * frame.step[k]);
  };
  return {at(0), at(1), at(2)};
}

}  // namespace

BackBlockFrame backFrameOf(const Box& viewBlock) {
  BackBlockFrame frame;
  if (viewBlock.empty()) return frame;
  frame.origin = viewBlock.low;
  // A little over a 65535th, so that the last corner is at least the high one (checked per
  // block all the same).
  frame.step = (viewBlock.high - viewBlock.low) * ((1.0 + 0x1p-20) / kLastStep);
  return frame;
}

BackBlockTest testOf(const BackBlock& block, const BackBlockFrame& frame) {
  BackBlockTest test;
  if (!block.skippable || block.box.empty()) return test;
  for (int k = 0; k < 3; ++k) {
    if (!stepDown(block.box.low[k], frame.origin[k], frame.step[k], test.low[k]) ||
        !stepUp(block.box.high[k], frame.origin[k], frame.step[k], test.high[k]))
      return BackBlockTest{};
  }
  // The axis in float, a; the angle widened by the angle between c and â = a/|a|, at most
  // the chord |c − â| (times 1 + 1e-6: the arc over the chord, tiny here) (BackFacingBlocks.h).
  const glm::vec3 rounded(block.axis);
  const glm::dvec3 a(rounded);
  const double length = glm::length(a);
  const double turn = glm::length(block.axis - a / length) * (1.0 + 1e-6) + 1e-15;
  const double angle = block.angle + turn;
  // The library's cosine and sine, the division and the product: a few unit roundoffs.
  test.cosAngle = floatDown(std::cos(angle) / length * (1.0 - 1e-14));
  test.sinAngle = floatUp(std::sin(angle) * (1.0 + 1e-14));
  FACET_ASSERT(test.cosAngle > 0.0F && angle < 1.6);
  for (int k = 0; k < 3; ++k)
    test.axis[k] = rounded[k];
  test.minDoubleArea = floatDown(block.minDoubleArea);
  test.maxPerimeterPerDoubleArea = floatUp(block.maxPerimeterPerDoubleArea);
  // The ball about the stepped box's centre that holds the box (the pre-test's: a necessary
  // condition of the corners' test, whose verdict alone counts).
  const Box box = boxOf(test, frame);
  const glm::dvec3 center = ballCenterOf(test, frame);
  double radius = 0.0;
  for (int i = 0; i < 8; ++i)
    radius = std::max(radius, glm::length(box.corner(i) - center));
  test.ballRadius = floatUp(radius * (1.0 + 1e-12));
  return test;
}

Box boxOf(const BackBlockTest& block, const BackBlockFrame& frame) {
  Box box;
  box.low = lowOf(block, frame);
  box.high = highOf(block, frame);
  return box;
}

BackBlockCone coneOf(const BackBlockTest& block, const BackBlockFrame& frame) {
  BackBlockCone cone;
  cone.box = boxOf(block, frame);
  cone.ballCenter = ballCenterOf(block, frame);
  cone.ballRadius = block.ballRadius;
  cone.axis = glm::dvec3(block.axis[0], block.axis[1], block.axis[2]);
  cone.cosAngle = block.cosAngle;
  cone.sinAngle = block.sinAngle;
  cone.minDoubleArea = block.minDoubleArea;
  cone.maxPerimeterPerDoubleArea = block.maxPerimeterPerDoubleArea;
  return cone;
}

BackBlockCone coneOf(const BackBlock& block) {
  BackBlockCone cone;
  cone.box = block.box;
  if (!block.box.empty()) {
    cone.ballCenter = centerOf(block.box.low, block.box.high);
    cone.ballRadius = 0.5 * glm::length(block.box.high - block.box.low);
  }
  cone.axis = block.axis;
  cone.cosAngle = block.skippable ? block.cosAngle : 0.0;
  cone.sinAngle = block.sinAngle;
  cone.minDoubleArea = block.minDoubleArea;
  cone.maxPerimeterPerDoubleArea = block.maxPerimeterPerDoubleArea;
  return cone;
}

BackPointFlags pointFlagsOf(const BackBlock& block, std::size_t pointCount) {
  BackPointFlags flags;
  const std::size_t flagCount = (pointCount + kPointsPerNeededFlag - 1) >> kNeededPointBits;
  if (!block.scatteredPointFlags.empty() || flagCount >= kReadWholeBackBlock) {
    flags.lowFirst = kReadWholeBackBlock;
    return flags;
  }
  const auto range = [](const PointSpan& span, std::uint32_t& first, std::uint32_t& end) {
    if (span.first > span.last) return;  // no point: first == end == 0
    first = static_cast<std::uint32_t>(span.first >> kNeededPointBits);
    end = static_cast<std::uint32_t>((span.last >> kNeededPointBits) + 1);
  };
  range(block.lowPoints, flags.lowFirst, flags.lowEnd);
  range(block.highPoints, flags.highFirst, flags.highEnd);
  return flags;
}

BackFaceTest::BackFaceTest(const FrameTransform& transform)
    : transform_(transform),
      c_(transform.constants()),
      margin_(ScopedBackBlockSettings::current().margin) {
  scaleX_ = c_.halfWidth * kSubpixelScale;
  scaleY_ = c_.halfHeight * kSubpixelScale;
  const glm::dvec3 cx(c_.clipX), cy(c_.clipY);
  rowX_ = glm::length(cx);
  rowY_ = glm::length(cy);
  const double rotation = glm::dot(c_.right, glm::cross(c_.up, c_.back));  // det R, ±1
  if (c_.parallel) {
    const glm::dvec3 w = glm::cross(cx, cy);
    const glm::dvec3 q =
        scaleX_ * scaleY_ * rotation * (c_.right * w.x + c_.up * w.y + c_.back * w.z);
    areaScale_ = glm::length(q);
    usable_ = areaScale_ > 0.0 && std::isfinite(areaScale_);
    if (usable_) awayFromViewer_ = -q / areaScale_;
    return;
  }
  // M = [cx; cy; (0, 0, −1)] on view coordinates.
  const double k = -(cx.x * cy.y - cx.y * cy.x) * rotation * scaleX_ * scaleY_;
  areaScale_ = std::abs(k);
  facingSign_ = k > 0.0 ? -1.0 : 1.0;
  usable_ = c_.clipX.w == 0.0 && c_.clipY.w == 0.0 && areaScale_ > 0.0 && std::isfinite(k);
}

// A necessary condition for step 3, from the box's bounding ball (center m, radius r) in
// place of its eight corners: every corner u has c·u ≤ c·(m − E) + r and |u⊥| ≥ |(m − E)⊥| − r,
// so the corners' D is at most what this tests. It rejects the blocks that face the viewer
// (half of them) at an eighth of the cost; any block it passes, the corners decide.
bool BackFaceTest::mayFaceAway(const BackBlockCone& block) const {
  if (!usable_ || !(block.cosAngle > 0.0)) return false;  // cosAngle 0: not skippable
  return ballMayFaceAway(block.ballCenter, block.ballRadius, block.axis, block.cosAngle,
                         block.sinAngle);
}

// The same on the compact record, decoding only what it reads (the ball and the cone).
bool BackFaceTest::mayFaceAway(const BackBlockTest& block, const BackBlockFrame& frame) const {
  if (!usable_ || !(block.cosAngle > 0.0F)) return false;  // cosAngle 0: not skippable
  const glm::dvec3 center = c_.parallel ? glm::dvec3(0.0) : ballCenterOf(block, frame);
  return ballMayFaceAway(center, block.ballRadius,
                         glm::dvec3(block.axis[0], block.axis[1], block.axis[2]), block.cosAngle,
                         block.sinAngle);
}

// Step 3 on the box's world corners of a block that passed the ball's pre-test: D, or a
// value ≤ 0 when the block's cone does not face away from every corner.
// Inlined: its box and cone are decoded into the caller's registers just before (called out of
// line, reading them back through memory cost the 2M cull a third more on-CPU time).
[[gnu::always_inline]] inline double BackFaceTest::facingMargin(const BackBlockCone& block) const {
  const glm::dvec3 axis = facingAxis(block.axis);
  // The largest squares, rooted once: the same values as the largest roots (a correctly
  // rounded square root is monotonic). A corner's u = corner − E takes each coordinate from
  // low − E or high − E, so the products of the dot products are formed once per coordinate
  // and side (the same products, summed in glm's order: the same values as per corner).
  const glm::dvec3 low = block.box.low - c_.eye, high = block.box.high - c_.eye;
  const glm::dvec3 side[2] = {low, high};
  double squares[3][2], alongs[3][2];
  for (int k = 0; k < 3; ++k) {
    for (int h = 0; h < 2; ++h) {
      squares[k][h] = side[h][k] * side[h][k];
      alongs[k][h] = axis[k] * side[h][k];
    }
  }
  double reachSquared = 0.0, minAlong = std::numeric_limits<double>::infinity(),
         maxAcrossSquared = 0.0;
  const double parallelAlong = glm::dot(axis, awayFromViewer_);
  const glm::dvec3 parallelAcross = awayFromViewer_ - parallelAlong * axis;
  for (int i = 0; i < 8; ++i) {
    const int x = i & 1, y = (i >> 1) & 1, z = i >> 2;
    reachSquared = std::max(reachSquared, squares[0][x] + squares[1][y] + squares[2][z]);
    if (c_.parallel) continue;
    const double along = alongs[0][x] + alongs[1][y] + alongs[2][z];
    const glm::dvec3 across = glm::dvec3(side[x].x, side[y].y, side[z].z) - along * axis;
    minAlong = std::min(minAlong, along);
    maxAcrossSquared = std::max(maxAcrossSquared, glm::dot(across, across));
  }
  if (c_.parallel) {
    minAlong = parallelAlong;
    maxAcrossSquared = glm::dot(parallelAcross, parallelAcross);
  }
  // Less this test's rounding of u and its parts.
  return block.cosAngle * minAlong - block.sinAngle * std::sqrt(maxAcrossSquared) -
         1e-12 * (c_.parallel ? 1.0 : std::sqrt(reachSquared));
}

ClipBounds BackFaceTest::clipBounds(const Box& box) const {
  ClipBounds bounds;
  ClipPoint corners[8];
  if (!transform_.boxInsideClipVolume(box, corners)) return bounds;  // step 1
  if (!margin_) {
    bounds.inside = true;
    return bounds;
  }
  // Nx and Ny bounded by the largest |clip x| and |clip y| over the smallest w (w > 0 at
  // every corner, step 1): two divisions rather than sixteen, a bound a little wider.
  double minW = std::numeric_limits<double>::infinity(), maxW = 0.0, maxX = 0.0, maxY = 0.0;
  double reachSquared = 0.0;
  for (int i = 0; i < 8; ++i) {
    const ClipPoint& corner = corners[i];
    const double w = c_.parallel ? corner.h : corner.d;
    minW = std::min(minW, w);
    maxW = std::max(maxW, w);
    maxX = std::max(maxX, std::abs(corner.x));
    maxY = std::max(maxY, std::abs(corner.y));
    const glm::dvec3 u = box.corner(i) - c_.eye;
    reachSquared = std::max(reachSquared, glm::dot(u, u));
  }
  const double ndcX = maxX / minW * (1.0 + 1e-15), ndcY = maxY / minW * (1.0 + 1e-15);
  if (c_.parallel) minW = maxW = 1.0;
  const double reach = std::sqrt(reachSquared);
  // Step 1's outcode margin, 1e-9·(w + |x|), must cover the transform's rounding of clip x
  // and y (~u·|row|·reach): a tenth of it at most.
  if (!(kUnitRoundoff * std::max(rowX_, rowY_) * reach <= 1e-10 * minW)) return bounds;
  // Step 4: the transform's rounding of a window coordinate, generously bounded: window x is
  // clip x / d, so the rounding of d (~u·reach) enters multiplied by |x/d| too (review20c).
  const double roundingX = 32.0 * kUnitRoundoff * scaleX_ *
                           ((rowX_ + ndcX) * reach / minW + std::abs(c_.clipX.w) + ndcX + 1.0);
  const double roundingY = 32.0 * kUnitRoundoff * scaleY_ *
                           ((rowY_ + ndcY) * reach / minW + std::abs(c_.clipY.w) + ndcY + 1.0);
  if (!(std::max(roundingX, roundingY) <= kLargestRounding)) return bounds;
  const double edgeScale = c_.parallel ? scaleX_ * rowX_ + scaleY_ * rowY_
                                       : scaleX_ * (rowX_ + ndcX) + scaleY_ * (rowY_ + ndcY);
  bounds.areaPerFacing = areaScale_ / (maxW * maxW * maxW);  // X = D · this
  bounds.edgePerLength = edgeScale / minW;                   // Y
  bounds.inside = true;
  return bounds;
}

// Step 5.
bool BackFaceTest::culledWithin(const BackBlockCone& block, double facing,
                                const ClipBounds& bounds) const {
  if (!(facing > 0.0) || !bounds.inside) return false;
  if (!margin_) return true;
  const double x = facing * bounds.areaPerFacing;
  const double perArea = x * (1.0 - kSlack) - kSnapDelta * block.maxPerimeterPerDoubleArea *
                                                  bounds.edgePerLength * (1.0 + kSlack);
  return perArea > 0.0 &&
         block.minDoubleArea * perArea > 2.0 * kSnapDelta * kSnapDelta * (1.0 + kSlack);
}

bool BackFaceTest::certainlyCulled(const BackBlockCone& block) const {
  // Most blocks that are not skipped face the viewer: the ball rejects them before any corner.
  if (!mayFaceAway(block)) return false;
  FACET_ASSERT(!block.box.empty());  // cosAngle > 0: skippable
  const double facing = facingMargin(block);
  if (!(facing > 0.0)) return false;
  return culledWithin(block, facing, clipBounds(block.box));
}

bool BackFaceTest::certainlyCulled(const BackBlockTest& block, const BackBlockFrame& frame) const {
  if (!usable_ || !(block.cosAngle > 0.0F)) return false;
  return certainlyCulled(coneOf(block, frame));
}

bool BackFaceTest::certainlyCulled(const BackBlock& block) const {
  return certainlyCulled(coneOf(block));
}

bool BackFaceTest::culledPastPreTest(const BackBlockTest& block, const BackBlockFrame& frame,
                                     ParentClipBounds& parent) const {
  BackBlockCone cone;  // what steps 3 and 5 read (not the ball), decoded here, in registers
  cone.box.low = lowOf(block, frame);
  cone.box.high = highOf(block, frame);
  cone.axis = glm::dvec3(block.axis[0], block.axis[1], block.axis[2]);
  cone.cosAngle = block.cosAngle;
  cone.sinAngle = block.sinAngle;
  cone.minDoubleArea = block.minDoubleArea;
  cone.maxPerimeterPerDoubleArea = block.maxPerimeterPerDoubleArea;
  FACET_ASSERT(!cone.box.empty());  // mayFaceAway passed: cosAngle > 0, skippable
  const double facing = facingMargin(cone);
  if (!(facing > 0.0)) return false;
  if (!parent.measured) {
    parent.bounds = clipBounds(*parent.box);
    parent.measured = true;
  }
  return culledWithin(cone, facing, parent.bounds);
}

ScopedBackBlockSettings::ScopedBackBlockSettings(Settings settings)
    : previous_(settingsOnThisThread) {
  settingsOnThisThread = settings;
}

ScopedBackBlockSettings::~ScopedBackBlockSettings() {
  settingsOnThisThread = previous_;
}

ScopedBackBlockSettings::Settings ScopedBackBlockSettings::current() {
  return settingsOnThisThread;
}

}  // namespace facet::detail
