#include "Resolve.h"

namespace facet::detail {
namespace {

template <bool kDepth>
void resolveTile(const ResolveContext& context, const PixelBounds& tile,
                 const FrameTransform& frameTransform) {
  // Locals: the color stores (bytes) may alias anything, which would reload these per pixel.
  const FrameTransform transform = frameTransform;
  const Rgba8* colors = context.colors;
  const Rgba8 background = context.background;
  for (int y = tile.y0; y <= tile.y1; ++y) {
    const std::size_t row = static_cast<std::size_t>(y) * context.width;
    const std::int32_t* ids = context.polygonId + row;
    Rgba8* color = context.color + row;
    float* depth = context.depth + row;
    for (int x = tile.x0; x <= tile.x1; ++x) {
      const std::int32_t id = ids[x];
      color[x] = id < 0 ? background : colors[static_cast<std::size_t>(id)];
    }
    if constexpr (kDepth) {
      for (int x = tile.x0; x <= tile.x1; ++x)
        depth[x] = ids[x] < 0 ? 1.0f : transform.windowDepth(depth[x]);
    }
  }
}

}  // namespace

ResolveRoutineChoice chooseResolveRoutine(bool depth) {
  if (depth) return {resolveTile<true>, "colors and window depths"};
  return {resolveTile<false>, "colors"};
}

bool resolveTiles(PhaseRunner& runner, const TileGrid& grid, const ResolveContext& context,
                  ResolveRoutine routine, const FrameTransform& transform) {
  return runner.run(Phase::Resolve, grid.count(),
                    [&](std::size_t t) { routine(context, grid.bounds(t), transform); });
}

}  // namespace facet::detail
