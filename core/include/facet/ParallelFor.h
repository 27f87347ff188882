#pragma once

/// @file ParallelFor.h
/// Blocks of work spread over threads, for the parts of the core that run outside a render
/// (the vertex normals of VertexNormals.h, the quality modes' per-mesh preparation).

#include <cstddef>
#include <functional>

namespace facet {

class Renderer;

/// Runs work(begin, end) for the blocks [i · grain, min(count, (i + 1) · grain)) of [0, count),
/// in any order and on any threads, and returns when all are done — Renderer::parallelFor,
/// for one. Empty: one block after another on the calling thread.
using ParallelFor = std::function<void(std::size_t count, std::size_t grain,
                                       const std::function<void(std::size_t, std::size_t)>& work)>;

/// Renderer::parallelFor of `renderer` (which must outlive the result) as a ParallelFor.
ParallelFor parallelOn(Renderer& renderer);

}  // namespace facet
