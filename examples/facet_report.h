// facet-render --report: error against run time for every quality mode, on a built-in set
// (the analytic sphere at a sweep of tessellations, the bunny, fandisk) and the user's
// meshes. See facet_report.cxx.

#pragma once

#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <functional>
#include <string>
#include <utility>
#include <vector>

struct ReportOptions
{
  /// The meshes to report on besides the built-in set, read by facet-render.
  std::vector<std::pair<std::string, vtkSmartPointer<vtkPolyData>>> Meshes;
  /// Segments around the analytic sphere's tessellations (empty: no sphere).
  std::vector<int> Sweep{ 8, 16, 32, 64, 128, 256, 512, 1024 };
  bool BuiltinMeshes = true; ///< the bunny and fandisk
  std::string MeshFolder;    ///< where the built-in meshes are
  /// Reads a mesh file (facet-render's reader); throws for what cannot be read.
  std::function<vtkSmartPointer<vtkPolyData>(const std::string& path)> Read;
  int Width = 1920, Height = 1080;
  int Repeats = 3; ///< timed renders per mode (the median is reported)
  int ReferenceSamples =
    128; ///< per pixel, for the converged references (README: 128 converges a mesh at 1080p)
  double MaximumError = 2.0; ///< the adaptive mode's budget, 8-bit units
  int Threads = 0;
  std::string Prefix = "report"; ///< writes PREFIX.csv and PREFIX.png
  std::string PlotScript;        ///< the matplotlib script that draws PREFIX.png
  bool Progress = true;
};

/// Renders, times and measures; prints the Markdown table to stdout; writes the CSV and the
/// plot. Returns the exit code; throws std::runtime_error for what the user must fix.
int RunReport(const ReportOptions& options);
