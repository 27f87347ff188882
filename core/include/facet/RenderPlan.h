#pragma once

/// @file RenderPlan.h
/// The work a render will do, decided once from the scene before any polygon is touched
/// ("leave out what the scene does not need"), and what the render then counted.

#include <cstddef>
#include <string>

#include "facet/Scene.h"

namespace facet {

/// Which code paths a render takes. Every flag that is false is work skipped.
struct RenderPlan {
  Visibility visibility = Visibility::ZBuffer;
  bool depthTest = true;     ///< z-buffer mode
  bool sortByDepth = false;  ///< painter mode: sort polygons by centroid depth
  /// Some light other than the ambient one reaches the scene. Without one, a polygon's color
  /// does not depend on its orientation: no normal is computed, and a mesh without
  /// per-polygon colors is shaded once for all its polygons.
  bool directLighting = false;
  bool positionalLights = false;  ///< point or spot lights: per-polygon distance and angle
  bool specular = false;          ///< some material has Ks > 0 under a direct light
  /// Polygons seen from their back (Conventions.h, "Facing") are lit with the normal flipped.
  bool twoSidedLighting = true;
  /// The direction to the viewer is needed (specular).
  bool viewerDirection = false;
  /// Polygon centers are needed (positional lights, or a perspective viewer direction).
  bool polygonCenters = false;
  bool backfaceCulling = false;  ///< some material culls back faces
  /// Some mesh is marked MeshView::closedSurface: its back faces are skipped in frames where
  /// the near plane does not cut it (RenderStats::closedMeshesSkippingBackFaces).
  bool closedSurfaces = false;
  bool parallelProjection = false;
  /// The routines chosen for this render (llvmpipe's habit: pick the routine once, not test
  /// per triangle or pixel): painting a tile, setting up a mesh's polygons and shading them.
  /// "per mesh" when meshes differ; the set-up's is known once the render has transformed.
  const char* rasterRoutine = "";
  const char* setupRoutine = "";
  const char* shadeRoutine = "";
  int threads = 1;
  int tileSize = 0;  ///< square tiles of this many pixels, each painted by one thread
  int tilesX = 0, tilesY = 0;
  int width = 0, height = 0;
  std::size_t meshes = 0;
  std::size_t points = 0;
  std::size_t polygons = 0;

  /// A few lines saying what will be done and what is left out.
  std::string describe() const;
};

/// What one render did and what it cost. Times are wall-clock seconds.
struct RenderStats {
  RenderPlan plan;
  double validateSeconds = 0.0;   ///< mesh structure checks
  double transformSeconds = 0.0;  ///< points to window coordinates (and painter's sort)
  double setupSeconds = 0.0;      ///< clip, cull, triangulate, bin
  double rasterSeconds = 0.0;     ///< clear and paint the tiles (depth and polygon ids)
  double shadeSeconds = 0.0;      ///< light the visible polygons, color the pixels
  double totalSeconds = 0.0;

  std::size_t polygonsDrawn = 0;  ///< sent to the tiles
  /// Lit: the polygons that won a pixel while painting (those visible in the image, and any
  /// overdrawn later).
  std::size_t polygonsShaded = 0;
  std::size_t polygonsCulled = 0;      ///< back-facing, culled or hidden (closed surface)
  std::size_t polygonsOutside = 0;     ///< outside the view, or covering no pixel center
  std::size_t polygonsDegenerate = 0;  ///< fewer than 3 points, or zero area
  std::size_t polygonsNonFinite = 0;   ///< using a point with a NaN or infinite coordinate
  std::size_t trianglesBinned = 0;     ///< triangles handed to the tiles
  std::size_t trianglesClipped = 0;    ///< triangles that went through the clipper
  std::size_t fragmentsWritten = 0;    ///< pixel writes, counting overdraw
  std::size_t pixelsCovered = 0;       ///< pixels showing a polygon at the end
  std::size_t closedMeshesSkippingBackFaces = 0;  ///< closed meshes wholly in front of near
  bool aborted = false;                           ///< the progress callback asked to stop
};

}  // namespace facet
