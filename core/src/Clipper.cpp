#include "Clipper.h"

#include <algorithm>
#include <iterator>

#include "Assert.h"

namespace facet::detail {
namespace {

ClipPoint lerp(const ClipPoint& from, const ClipPoint& to, double t) {
  return {from.x + t * (to.x - from.x), from.y + t * (to.y - from.y), from.d + t * (to.d - from.d),
          from.h + t * (to.h - from.h)};
}

// The point where the edge from `inside` (distance ≥ 0) to `outside` (distance < 0) crosses
// the plane. Both fractions are computed directly rather than one as 1 minus the other, and
// the smaller one is used, so the point is exact near either end.
ClipVertex intersect(const FrameTransform& transform, int plane, const ClipVertex& inside,
                     double insideDistance, const ClipVertex& outside, double outsideDistance) {
  const double span = insideDistance - outsideDistance;  // > 0: no cancellation
  const double fromInside = insideDistance / span, fromOutside = -outsideDistance / span;
  FACET_ASSERT(fromInside >= 0.0 && fromInside <= 1.0 && fromOutside >= 0.0);
  ClipVertex crossing{fromInside <= fromOutside ? lerp(inside.clip, outside.clip, fromInside)
                                                : lerp(outside.clip, inside.clip, fromOutside),
                      ClipVertex::kNewVertex,
                      static_cast<std::uint8_t>(inside.onEdges & outside.onEdges)};
  transform.placeOnPlane(crossing.clip, plane);
  return crossing;
}

int clipAgainstPlane(const FrameTransform& transform, int plane, const ClipVertex* in, int count,
                     ClipVertex* out) {
  int written = 0;
  for (int i = 0; i < count; ++i) {
    const ClipVertex& current = in[i];
    const ClipVertex& next = in[(i + 1) % count];
    const double currentDistance = transform.planeDistance(current.clip, plane);
    const double nextDistance = transform.planeDistance(next.clip, plane);
    const bool currentInside = currentDistance >= 0.0;
    const bool nextInside = nextDistance >= 0.0;
    if (currentInside) out[written++] = current;
    if (currentInside && !nextInside) {
      out[written++] = intersect(transform, plane, current, currentDistance, next, nextDistance);
    } else if (!currentInside && nextInside) {
      out[written++] = intersect(transform, plane, next, nextDistance, current, currentDistance);
    }
  }
  return written;
}

}  // namespace

int clipTriangle(const FrameTransform& transform, const ClipVertex (&triangle)[3],
                 std::uint32_t planes, ClipVertex (&out)[kMaxClippedVertices]) {
  ClipVertex scratch[kMaxClippedVertices];
  std::copy(std::begin(triangle), std::end(triangle), out);
  int count = 3;
  for (int plane = 0; plane < kClipPlaneCount && count > 0; ++plane) {
    if ((planes & (1u << plane)) == 0) continue;
    count = clipAgainstPlane(transform, plane, out, count, scratch);
    std::copy(scratch, scratch + count, out);
  }
  return count >= 3 ? count : 0;
}

}  // namespace facet::detail
