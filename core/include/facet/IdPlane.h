#pragma once

/// @file IdPlane.h
/// The renderer's polygon id plane (FramebufferView::polygonId: -1 for the background) turned
/// into a caller's 64-bit ids, for a front end whose ids are the polygon ids shifted (VTK's
/// CellId of a polydata: its polygons are numbered after its verts and lines).

#include <cstddef>
#include <cstdint>

namespace facet {

/// A plane of this many bytes or more is streamed to memory by widenPolygonIds: it would not
/// stay in the caches for whoever reads it next, and a plain store reads each line before
/// writing it (the write-allocate read of 16 MB of 64-bit ids at 1080p).
inline constexpr std::size_t kStreamedPlaneBytes = std::size_t{4} << 20;

/// ids[0, count) into out[0, count): first + id where a polygon shows (id >= 0), -1 where none
/// (id < 0). In SIMD lanes on the best instruction set of this CPU (the same bytes on every
/// one); `stream`: by streaming stores (no write-allocate read), fenced before it returns,
/// for a plane of kStreamedPlaneBytes or more. Defined in Resolve.cpp, beside the resolve's
/// colors: both write rows through one Highway store loop. `out` is written by SIMD stores and
/// std::memcpy only, never through an std::int64_t lvalue, so it may be the address of another
/// signed 64-bit integer type's plane (VTK's vtkIdType is long long where std::int64_t is long:
/// stores of one type read back as the other would break strict aliasing).
void widenPolygonIds(const std::int32_t* ids, std::int64_t* out, std::size_t count,
                     std::int64_t first, bool stream);

}  // namespace facet
