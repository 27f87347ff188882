// facet-render --report: every quality mode (flat, Gouraud, Phong, adaptive × 1, 4, 16
// samples) on every mesh, timed in process (the median of several renders, the mesh's
// ShadingMesh prepared once before, as the filter keeps it) and measured against a
// converged reference: the exact sphere for the sphere sweep (AnalyticReference.h), the
// Phong mesh reference for the other meshes (MeshReference.h). Flat rows also show the
// error Facet predicts for itself (QualityRenderer.h). Output: a Markdown table on stdout,
// PREFIX.csv, and PREFIX.png drawn by facet_report_plot.py (matplotlib): error against time
// per mesh, log-log, with the Pareto front.

#include "facet_report.h"

#include "vtkCellArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkSphereSource.h"
#include "vtkTriangleFilter.h"

#include <glm/trigonometric.hpp>

#include "facet/AnalyticReference.h"
#include "facet/ImageMetrics.h"
#include "facet/MeshReference.h"
#include "facet/QualityRenderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>

namespace {
using Clock = std::chrono::steady_clock;

struct Entry
{
  std::string Group; // rows of one group share a plot
  std::string Name;
  facet::Mesh Mesh;
  bool Sphere = false; // the unit sphere: compared with the exact one
};

struct Row
{
  std::string Group, Mesh, Mode;
  int Samples = 1;
  double Milliseconds = 0.0;
  facet::ImageError Error;
  std::optional<double> Predicted;
};

// The report's scene: a warm, shiny surface (the reference tests' material,
// tests/support/ReferenceScenes.cpp) under a key light and a bluish fill light, both
// directional, as VTK's light kit and headlight are.
facet::Material ReportMaterial()
{
  facet::Material material;
  material.color = { 0.9f, 0.7f, 0.5f };
  material.specular = 0.4;
  material.specularPower = 20.0;
  return material;
}

struct Frame
{
  glm::dvec3 Center{ 0.0 };
  double Radius = 1.0;
};

Frame FrameOf(const facet::Mesh& mesh)
{
  glm::dvec3 low(INFINITY), high(-INFINITY);
  for (const glm::dvec3& p : mesh.points)
  {
    low = glm::min(low, p);
    high = glm::max(high, p);
  }
  Frame frame{ 0.5 * (low + high), 0.0 };
  for (const glm::dvec3& p : mesh.points)
  {
    frame.Radius = std::max(frame.Radius, glm::length(p - frame.Center));
  }
  return frame;
}

facet::LightSet ReportLights()
{
  facet::LightSet lights;
  lights.lights.push_back(facet::DirectionalLight{ { -1, -1, -2 }, facet::Color(0.8f) });
  lights.lights.push_back(
    facet::DirectionalLight{ { 0.6, -0.2, -1 }, facet::Color(0.35f, 0.35f, 0.5f) });
  return lights;
}

// Looking along (0.2, -0.3, -1) at the bounding sphere, which fills the view's height.
facet::Camera ReportCamera(const Frame& frame)
{
  facet::Camera camera;
  const glm::dvec3 direction = glm::normalize(glm::dvec3(0.2, -0.3, -1.0));
  const double distance = frame.Radius / std::sin(glm::radians(15.0));
  camera.focalPoint = frame.Center;
  camera.position = frame.Center - distance * direction;
  camera.nearClip = distance - 1.01 * frame.Radius;
  camera.farClip = distance + 1.01 * frame.Radius;
  return camera;
}

// A vtkPolyData's polygons (and strips, as triangles) as a core mesh.
facet::Mesh ToMesh(vtkPolyData* input)
{
  vtkSmartPointer<vtkPolyData> polyData = input;
  if (input->GetNumberOfStrips() > 0)
  {
    vtkNew<vtkTriangleFilter> triangles;
    triangles->SetInputData(input);
    triangles->PassVertsOff();
    triangles->PassLinesOff();
    triangles->Update();
    polyData = triangles->GetOutput();
  }
  facet::Mesh mesh;
  for (vtkIdType i = 0; i < polyData->GetNumberOfPoints(); ++i)
  {
    double p[3];
    polyData->GetPoint(i, p);
    mesh.addPoint({ p[0], p[1], p[2] });
  }
  vtkCellArray* polys = polyData->GetPolys();
  vtkIdType count = 0;
  const vtkIdType* ids = nullptr;
  std::vector<std::int64_t> corners;
  for (polys->InitTraversal(); polys->GetNextCell(count, ids);)
  {
    corners.assign(ids, ids + count);
    mesh.addPolygon(corners);
  }
  return mesh;
}

facet::Mesh UnitSphere(int segments)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(1.0);
  sphere->SetThetaResolution(segments);
  sphere->SetPhiResolution(segments / 2 + 1);
  sphere->Update();
  return ToMesh(sphere->GetOutput());
}

std::vector<Entry> EntriesOf(const ReportOptions& options)
{
  std::vector<Entry> entries;
  for (const int segments : options.Sweep)
  {
    entries.push_back(
      { "sphere", "sphere " + std::to_string(segments), UnitSphere(segments), true });
  }
  if (options.BuiltinMeshes)
  {
    for (const char* file : { "stanford-bunny.obj", "fandisk.obj" })
    {
      const std::string path = options.MeshFolder + "/" + file;
      if (!std::filesystem::is_regular_file(path))
      {
        throw std::runtime_error("the built-in mesh '" + path + "' is missing");
      }
      entries.push_back({ file, file, ToMesh(options.Read(path)), false });
    }
  }
  for (const auto& [name, polyData] : options.Meshes)
  {
    entries.push_back({ name, name, ToMesh(polyData), false });
  }
  return entries;
}

struct Mode
{
  std::string Name;
  facet::QualitySettings Settings;
};

std::vector<Mode> ModesOf(double budget)
{
  std::vector<Mode> modes;
  for (const int samples : { 1, 4, 16 })
  {
    modes.push_back({ "flat", { facet::Shading::Flat, samples } });
    modes.push_back({ "Gouraud", { facet::Shading::Gouraud, samples } });
    modes.push_back({ "Phong", { facet::Shading::Phong, samples } });
    char name[64];
    std::snprintf(name, sizeof name, "adaptive (e = %g)", budget);
    modes.push_back({ name, { facet::Shading::Flat, samples, budget } });
  }
  return modes;
}

class Progress
{
public:
  Progress(std::size_t steps, bool shown)
    : Steps(steps)
    , Shown(shown)
  {}
  void Step(const std::string& what)
  {
    if (!this->Shown)
    {
      return;
    }
    const double fraction = static_cast<double>(this->Done++) / static_cast<double>(this->Steps);
    const int filled = static_cast<int>(fraction * 30.0);
    std::fprintf(stderr,
      "\r\033[Kreport [%.*s%*s] %3d%% %s",
      filled,
      "##############################",
      30 - filled,
      "",
      static_cast<int>(fraction * 100.0),
      what.c_str());
    std::fflush(stderr);
  }
  void Finish() const
  {
    if (this->Shown)
    {
      std::fprintf(stderr, "\r\033[Kreport: done\n");
    }
  }

private:
  std::size_t Steps, Done = 0;
  bool Shown;
};

double Median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// Every mode of one mesh, against `reference`.
void ReportMesh(const Entry& entry,
  const facet::Scene& scene,
  const std::vector<facet::ShadingMesh>& shading,
  const facet::Camera& camera,
  const facet::FloatImage& reference,
  const ReportOptions& options,
  Progress& progress,
  std::vector<Row>& rows)
{
  facet::Renderer renderer;
  renderer.setThreadCount(options.Threads);
  facet::QualityRenderer quality(renderer);
  facet::Framebuffer image(options.Width, options.Height);
  for (const Mode& mode : ModesOf(options.MaximumError))
  {
    progress.Step(
      entry.Name + ", " + mode.Name + " x" + std::to_string(mode.Settings.samplesPerPixel));
    Row row{ entry.Group, entry.Name, mode.Name, mode.Settings.samplesPerPixel };
    quality.render(scene, shading, camera, image, mode.Settings); // measured, and warms up
    row.Error = facet::compareImages(reference, facet::toFloatImage(image));
    std::vector<double> seconds;
    for (int i = 0; i < options.Repeats; ++i)
    {
      seconds.push_back(quality.render(scene, shading, camera, image, mode.Settings).totalSeconds);
    }
    row.Milliseconds = 1e3 * Median(seconds);
    if (mode.Settings.shading == facet::Shading::Flat && !mode.Settings.maximumError)
    {
      facet::QualitySettings estimate = mode.Settings;
      estimate.estimateError = true;
      row.Predicted = quality.render(scene, shading, camera, image, estimate).predictedRmse;
    }
    rows.push_back(row);
  }
}

std::string Cell(double value, const char* format)
{
  char text[32];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

void PrintTable(const std::vector<Row>& rows, const ReportOptions& options)
{
  std::printf("Error against time at %dx%d (8-bit units; time: median of %d renders)\n\n",
    options.Width,
    options.Height,
    options.Repeats);
  std::printf("| mesh | mode | samples | time ms | RMSE | max | PSNR dB | SSIM | silhouette %% | "
              "predicted RMSE |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const Row& r : rows)
  {
    std::printf("| %s | %s | %d | %s | %s | %s | %s | %s | %s | %s |\n",
      r.Mesh.c_str(),
      r.Mode.c_str(),
      r.Samples,
      Cell(r.Milliseconds, "%.1f").c_str(),
      Cell(r.Error.rmse, "%.2f").c_str(),
      Cell(r.Error.maxError, "%.0f").c_str(),
      Cell(r.Error.psnr, "%.1f").c_str(),
      r.Error.ssim ? Cell(*r.Error.ssim, "%.4f").c_str() : "",
      Cell(100.0 * r.Error.silhouetteFraction, "%.2f").c_str(),
      r.Predicted ? Cell(*r.Predicted, "%.2f").c_str() : "");
  }
}

void WriteCsv(const std::vector<Row>& rows, const std::string& path)
{
  std::ofstream csv(path);
  csv << "group,mesh,mode,samples,time_ms,rmse,max,psnr,ssim,silhouette_percent,predicted_rmse\n";
  for (const Row& r : rows)
  {
    csv << r.Group << ',' << r.Mesh << ',' << r.Mode << ',' << r.Samples << ',' << r.Milliseconds
        << ',' << r.Error.rmse << ',' << r.Error.maxError << ',' << r.Error.psnr << ','
        << (r.Error.ssim ? *r.Error.ssim : NAN) << ',' << 100.0 * r.Error.silhouetteFraction << ','
        << (r.Predicted ? *r.Predicted : NAN) << '\n';
  }
  if (!csv)
  {
    throw std::runtime_error("cannot write '" + path + "'");
  }
}
}

int RunReport(const ReportOptions& options)
{
  const std::vector<Entry> entries = EntriesOf(options);
  const std::size_t modes = ModesOf(options.MaximumError).size();
  Progress progress(entries.size() * (modes + 1), options.Progress);
  std::vector<Row> rows;
  std::optional<facet::FloatImage> sphereReference;
  for (const Entry& entry : entries)
  {
    const Frame frame = entry.Sphere ? Frame{} : FrameOf(entry.Mesh);
    const facet::Camera camera = ReportCamera(frame);
    facet::Scene scene;
    scene.meshes.push_back({ entry.Mesh.view(), ReportMaterial() });
    scene.lights = ReportLights();
    const std::vector<facet::ShadingMesh> shading{ facet::ShadingMesh(entry.Mesh.view()) };
    facet::ReferenceOptions referenceOptions;
    referenceOptions.samplesPerPixel = options.ReferenceSamples;
    referenceOptions.threads = options.Threads;
    progress.Step(entry.Name + ": reference");
    facet::FloatImage reference;
    if (entry.Sphere)
    {
      if (!sphereReference)
      {
        facet::AnalyticScene exact;
        exact.spheres.push_back({ glm::dvec3(0.0), 1.0, ReportMaterial() });
        exact.lights = scene.lights;
        sphereReference = facet::renderAnalyticReference(
          exact, camera, options.Width, options.Height, referenceOptions)
                            .image;
      }
      reference = *sphereReference;
    }
    else
    {
      const std::vector<facet::VertexNormals> normals{ shading[0].normals };
      reference = facet::renderMeshReference(
        scene, camera, options.Width, options.Height, referenceOptions, normals)
                    .image;
    }
    ReportMesh(entry, scene, shading, camera, reference, options, progress, rows);
  }
  progress.Finish();
  PrintTable(rows, options);
  const std::string csv = options.Prefix + ".csv", png = options.Prefix + ".png";
  WriteCsv(rows, csv);
  std::fprintf(stderr, "report: wrote %s\n", csv.c_str());
  if (options.PlotScript.empty())
  {
    return 0;
  }
  const std::string command =
    "/usr/bin/python3 '" + options.PlotScript + "' '" + csv + "' '" + png + "'";
  if (std::system(command.c_str()) != 0)
  {
    throw std::runtime_error("the plot failed: " + command);
  }
  std::fprintf(stderr, "report: wrote %s\n", png.c_str());
  return 0;
}
