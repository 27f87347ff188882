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
/// Counter-clockwise winding in window coordinates is front-facing (OpenGL's and VTK's
/// default).
///
/// **Depth.** Window depth in [0, 1]; 1 is the far plane and the background, the same
/// convention as VTK's z-buffer image (`vtkRenderWindow::GetZbufferData`).
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
