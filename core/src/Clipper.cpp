#include "Clipper.h"

#include <algorithm>
#include <iterator>

namespace facet::detail {
namespace {

ClipVertex intersect(const ClipVertex& inside, double insideDistance, const ClipVertex& outside,
                     double outsideDistance) {
  const double t = insideDistance / (insideDistance - outsideDistance);
  return {inside.clip + t * (outside.clip - inside.clip), ClipVertex::kNewVertex};
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
      out[written++] = intersect(current, currentDistance, next, nextDistance);
    } else if (!currentInside && nextInside) {
      out[written++] = intersect(next, nextDistance, current, currentDistance);
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
