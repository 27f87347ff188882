#pragma once

// VTK's own OpenGL renderer as the reference the agreement tests compare with: off screen,
// without multisampling, color and depth read back. Needs an X server (tests/plugin/
// xvfb_run.sh starts one).

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkWindowToImageFilter.h"

namespace facet_test {

// Renders the renderer off screen at width × height, without multisampling.
inline vtkSmartPointer<vtkRenderWindow> RenderOffScreen(vtkRenderer* renderer,
  int width,
  int height)
{
  auto window = vtkSmartPointer<vtkRenderWindow>::New();
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(width, height);
  window->AddRenderer(renderer);
  window->Render();
  return window;
}

// The window's color (RGB) or depth buffer.
inline vtkSmartPointer<vtkImageData> ReadBack(vtkRenderWindow* window, bool depth)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  if (depth)
  {
    grab->SetInputBufferTypeToZBuffer();
  }
  grab->Update();
  return grab->GetOutput();
}

} // namespace facet_test
