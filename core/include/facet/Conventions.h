#pragma once

/// @file Conventions.h
/// The conventions every part of Facet follows, written once. Other headers link here
/// instead of restating them.
///
/// **Coordinates.** Right-handed world. In view (camera) space the camera sits at the origin
/// and looks down −Z with +Y up, as in VTK and OpenGL. Transforms are named
/// destination-from-source: `viewFromWorld`, `clipFromView`.
///
/// **Window.** Pixel (0, 0) is the bottom-left pixel and row 0 is the bottom row, as
/// `glReadPixels` and `vtkWindowToImageFilter` return it. Pixel centers sit at +0.5.
///
/// **Facing.** Counter-clockwise winding seen by the viewer is front-facing (OpenGL's and
/// VTK's default). A triangle is decided by its exact integer window area, as OpenGL's
/// gl_FrontFacing (or, when the clipper cuts it, by its plane). A polygon of more vertices is
/// decided as a whole: its normal (`polygonNormal`, PolygonNormal.h) against the direction
/// to the viewer at its center (parallel projection: the view direction). It is lit from
/// that side and, when back faces are culled, dropped whole — never judged by one of its
/// triangles, which snapping can turn over.
///
/// **Depth.** Window depth in [0, 1]; 1 is the far plane and the background, the same
/// convention as VTK's z-buffer image (`vtkRenderWindow::GetZbufferData`): perspective
/// f(d − n)/(d(f − n)), parallel (d − n)/(f − n), for view distance d and clipping range
/// [n, f]. It is computed in double from the depth key below and rounded to the nearest
/// float, once per pixel.
///
/// Visibility is decided on another quantity, the depth key, larger = nearer: n/d in
/// perspective (the reversed float depth buffer: float keeps its 2^-24 relative precision at
/// every distance, so the nearer of two surfaces a few 1e-7 of their distance apart wins at
/// any far/near ratio up to 2^126), n − d in parallel projection (2^-24 of the distance from
/// the near plane). Keys are interpolated in double across each triangle from its unsnapped
/// vertex positions (for a mesh whose back faces are drawn, samples within 1/512 pixel
/// outside a polygon's edge use the snapped ones, so that silhouettes fold as culling would)
/// and rounded to float once per fragment. An exact tie keeps the front face over a back face
/// (where back faces are drawn); among polygons facing the same way, the polygon drawn first:
/// polygon order in z-buffer mode (scene order: mesh 0's polygons, then mesh 1's, ...).
///
/// **Angles.** Degrees in the public API wherever VTK uses degrees (view angle, cone angle,
/// spot angles); every such name ends in `Degrees`. Radians and cosines inside the core.
///
/// **Colors.** Linear float RGB in [0, 1]. Light contributions add; the sum saturates once,
/// at the end (`saturate`). 8-bit output rounds to nearest (`toByte`).
///
/// **Errors.** Bad input at the API boundary throws `facet::Error` whose message names the
/// offending value. Nothing to draw (culled, clipped away, degenerate) is not an error.

namespace facet {

/// Sub-pixel precision of the rasterizer's fixed-point window coordinates: 8 bits, i.e.
/// vertices snap to 1/256 of a pixel (as llvmpipe and D3D10-class hardware do).
inline constexpr int kSubpixelBits = 8;
inline constexpr int kSubpixelScale = 1 << kSubpixelBits;

/// Largest image side the rasterizer accepts, in pixels. Fixed-point window coordinates of
/// clipped geometry stay below 2^15 pixels, so edge functions fit in 64-bit integers exactly.
inline constexpr int kMaxImageSide = 16384;

}  // namespace facet
