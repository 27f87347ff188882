// facet-render: render a mesh file to a PNG with vtkFacetRenderFilter. Run with --help.

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFacetLight.h"
#include "vtkFacetRenderFilter.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataReader.h"
#include "vtkProperty.h"
#include "vtkSTLReader.h"
#include "vtkSmartPointer.h"
#include "vtkStringOutputWindow.h"
#include "vtkXMLPolyDataReader.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "facet_report.h"

namespace {
// A one-line error for the user; `usage` errors exit with 2, others with 1.
struct Failure : std::runtime_error
{
  Failure(const std::string& message, bool usage)
    : std::runtime_error(message)
    , Usage(usage)
  {}
  bool Usage;
};

[[noreturn]] void BadOption(const std::string& message)
{
  throw Failure(message + " (see facet-render --help)", true);
}

std::vector<std::string> Split(const std::string& text, char separator)
{
  std::vector<std::string> parts;
  std::stringstream stream(text);
  std::string part;
  while (std::getline(stream, part, separator))
  {
    parts.push_back(part);
  }
  return parts;
}

// Finite numbers separated by `separator`, as many as there are.
std::vector<double> ParseNumberList(const std::string& text,
  char separator,
  const std::string& option,
  const std::string& form)
{
  std::vector<double> values;
  for (const std::string& item : Split(text, separator))
  {
    std::size_t used = 0;
    double value = 0.0;
    try
    {
      value = std::stod(item, &used);
    }
    catch (const std::exception&)
    {
      used = 0;
    }
    if (used == 0 || used != item.size() || !std::isfinite(value))
    {
      BadOption(option + " expects " + form + " (finite numbers), got '" + text + "'");
    }
    values.push_back(value);
  }
  return values;
}

std::vector<double> ParseNumbers(const std::string& text,
  char separator,
  std::size_t count,
  const std::string& option,
  const std::string& form)
{
  std::vector<double> values = ParseNumberList(text, separator, option, form);
  if (values.size() != count)
  {
    BadOption(option + " expects " + form + ", got '" + text + "'");
  }
  return values;
}

using Vector3 = std::array<double, 3>;

Vector3 ParseVector(const std::string& text, const std::string& option, const std::string& form)
{
  const auto v = ParseNumbers(text, ',', 3, option, form);
  return { v[0], v[1], v[2] };
}

// --light: what kind, where, toward what, its cone and color.
struct LightSpec
{
  std::string Kind;          // headlight, directional, point, spot, linear-spot
  Vector3 Vector{ 0, 0, 0 }; // direction (directional) or position (point, spots)
  Vector3 Focal{ 0, 0, 0 };  // spots: where they point
  std::vector<double> Cone;  // spot: angle[, exponent]; linear-spot: full, falloff
  Vector3 Color{ 1, 1, 1 };
};

const char* const LightForms = "headlight, directional:DX,DY,DZ, point:X,Y,Z, "
                               "spot:X,Y,Z:FX,FY,FZ[:ANGLE[,EXP]] or "
                               "linear-spot:X,Y,Z:FX,FY,FZ[:FULL,FALLOFF]";

// The cone of a spot light, checked against the ranges vtkLight and vtkFacetLight accept.
std::vector<double> ParseCone(const std::string& kind, const std::string& text)
{
  const std::string option = "--light " + kind + " cone";
  if (kind == "spot")
  {
    const auto cone = ParseNumberList(text, ',', option, "ANGLE[,EXPONENT]");
    if (cone.empty() || cone.size() > 2 || cone[0] < 0 || cone[0] > 90 ||
      (cone.size() == 2 && (cone[1] < 0 || cone[1] > 128)))
    {
      BadOption(
        option + " expects ANGLE in [0, 90] degrees and EXPONENT in [0, 128], got '" + text + "'");
    }
    return cone;
  }
  const auto cone = ParseNumbers(text, ',', 2, option, "FULL,FALLOFF");
  if (cone[0] < 0 || cone[0] > 180 || cone[1] < 0 || cone[1] > 180)
  {
    BadOption(option + " expects FULL and FALLOFF in [0, 180] degrees, got '" + text + "'");
  }
  return cone;
}

LightSpec ParseLight(const std::string& text)
{
  LightSpec light;
  std::string body = text;
  if (const auto at = body.find('@'); at != std::string::npos)
  {
    light.Color = ParseVector(body.substr(at + 1), "--light color", "R,G,B");
    body.resize(at);
  }
  const std::vector<std::string> parts = Split(body, ':');
  light.Kind = parts.empty() ? "" : parts[0];
  const std::string option = "--light " + light.Kind;
  if (light.Kind == "headlight" && parts.size() == 1)
  {
    return light;
  }
  if ((light.Kind == "directional" || light.Kind == "point") && parts.size() == 2)
  {
    light.Vector = ParseVector(parts[1], option, "X,Y,Z");
    return light;
  }
  if ((light.Kind == "spot" || light.Kind == "linear-spot") &&
    (parts.size() == 3 || parts.size() == 4))
  {
    light.Vector = ParseVector(parts[1], option + " position", "X,Y,Z");
    light.Focal = ParseVector(parts[2], option + " focal point", "FX,FY,FZ");
    if (light.Vector == light.Focal)
    {
      BadOption(option + " points nowhere: its focal point is its position, in '" + text + "'");
    }
    if (parts.size() == 4)
    {
      light.Cone = ParseCone(light.Kind, parts[3]);
    }
    return light;
  }
  BadOption(std::string("--light expects ") + LightForms + ", got '" + text + "'");
}

// Settings left unset (std::nullopt) keep vtkFacetRenderFilter's defaults.
struct Options
{
  std::string Input;
  std::string Output;
  int Width = 800, Height = 600;
  double Azimuth = 0, Elevation = 0, Zoom = 1;
  bool Parallel = false;
  std::vector<LightSpec> Lights;
  std::optional<Vector3> Ambient;
  Vector3 Color{ 0.9, 0.9, 0.9 };
  std::string ColorBy;
  std::optional<std::array<double, 2>> Range;
  Vector3 Background{ 0.1, 0.1, 0.12 };
  bool Painter = false;
  int Interpolation = VTK_FLAT; // --shading
  int Samples = 1;
  double MaxError = 0.0;
  std::optional<int> Threads;
  bool Progress = false, Quiet = false, Help = false;
  bool Explain = false;
  // --report
  bool Report = false;
  std::vector<std::string> Inputs; // every positional argument
  bool SizeGiven = false;
  ReportOptions ReportSettings;
};

std::string Format(double value)
{
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

std::string Format(const double* values, int count)
{
  std::string text;
  for (int i = 0; i < count; ++i)
  {
    text += (i ? "," : "") + Format(values[i]);
  }
  return text;
}

// The help text, with the defaults read from Options and from the VTK classes themselves.
std::string UsageText()
{
  const Options tool;
  vtkNew<vtkFacetRenderFilter> filter;
  vtkNew<vtkFacetLight> light;
  const std::string size = std::to_string(tool.Width) + "x" + std::to_string(tool.Height);
  return R"(usage: facet-render MESH [options]

Renders a mesh with Facet, a CPU flat-shading rasterizer (no GPU, no display), and writes
a PNG. MESH is a .vtp, .vtk (polydata), .obj, .ply or .stl file.

options:
  -o, --output FILE       the PNG to write (default: MESH's name with .png, here)
  -s, --size WxH          image size in pixels (default: )" +
    size + R"()
      --azimuth DEG       turn the camera around the mesh, about the view up (default: )" +
    Format(tool.Azimuth) + R"()
      --elevation DEG     raise the camera over the mesh (default: )" +
    Format(tool.Elevation) + R"()
      --zoom FACTOR       magnify; 2 shows half as much (default: )" +
    Format(tool.Zoom) + R"()
      --parallel          parallel projection instead of perspective
  -l, --light SPEC        add a light (repeat for more; default: one headlight):
                            headlight[@R,G,B]
                            directional:DX,DY,DZ[@R,G,B]  (the direction it shines)
                            point:X,Y,Z[@R,G,B]           (world coordinates)
                            spot:X,Y,Z:FX,FY,FZ[:ANGLE[,EXP]][@R,G,B]
                              at X,Y,Z toward FX,FY,FZ; vtkLight's cone: cos^EXP of the
                              angle from the axis, none beyond ANGLE degrees (default: )" +
    Format(light->GetConeAngle()) + "," + Format(light->GetExponent()) + R"()
                            linear-spot:X,Y,Z:FX,FY,FZ[:FULL,FALLOFF][@R,G,B]
                              vtkFacetLight's cone: full within FULL degrees of the axis,
                              fading linearly to none over FALLOFF more (default: )" +
    Format(light->GetFullIntensityAngle()) + "," + Format(light->GetFalloffAngle()) + R"()
      --ambient R,G,B     scene ambient light (default: )" +
    Format(filter->GetAmbientLightColor(), 3) + R"()
      --color R,G,B       surface color (default: )" +
    Format(tool.Color.data(), 3) + R"()
      --color-by ARRAY    color by a point or cell data array, through a lookup table
      --range MIN,MAX     the values spanning the lookup table (default: the array's range)
      --shading MODE      flat, gouraud or phong (default: flat)
      --samples N         samples per pixel: 1, 4 or 16, averaged (default: 1)
      --max-error E       adaptive: polygons whose flat-shading error bound is within E
                          (8-bit units) stay flat, the others are Phong-shaded (default: off)
      --background R,G,B  (default: )" +
    Format(tool.Background.data(), 3) + R"()
      --painter           painter's algorithm instead of the z-buffer
  -t, --threads N         threads; 0 uses every core (default: )" +
    std::to_string(filter->GetNumberOfThreads()) + R"()
      --explain           print the render's plan after it: what ran, what each rule
                          left out and why, the time per phase
      --progress          always show the progress bar (default: on a terminal only)
  -q, --quiet             no progress bar and no summary
  -h, --help              this text

report mode: facet-render --report [MESH ...] [options]
  Renders every quality mode (flat, gouraud, phong, adaptive x 1, 4, 16 samples) of a
  built-in set (the analytic sphere at a sweep of tessellations, the bunny, fandisk) and
  of each MESH at 1920x1080 (or --size), times them (median in process) and measures them
  against converged references; prints a Markdown table, writes PREFIX.csv and the
  error-against-time plot PREFIX.png (/usr/bin/python3 with matplotlib).
  -o, --output PREFIX     (default: report)
      --sweep N,N,...     the sphere's segments, or "none" (default: 8,...,1024)
      --no-builtin        leave out the bunny and fandisk
      --repeats N         timed renders per mode (default: 3)
      --reference-samples N  per pixel, for the references (default: 128)

Colors are in [0, 1]. Example:
  facet-render bunny.obj -o bunny.png --size 1280x960 --azimuth 30 \
      --light point:0.3,0.4,0.5@1,0.8,0.6 --light headlight@0.3,0.3,0.4
)";
}

Vector3 ParseColor(const std::string& text, const std::string& option)
{
  const Vector3 c = ParseVector(text, option, "R,G,B");
  for (double channel : c)
  {
    if (channel < 0.0 || channel > 1.0)
    {
      BadOption(option + " channels must be in [0, 1], got '" + text + "'");
    }
  }
  return c;
}

Options ParseOptions(int argc, char** argv)
{
  Options o;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc)
      {
        BadOption(arg + " needs a value");
      }
      return argv[++i];
    };
    if (arg == "-h" || arg == "--help")
    {
      o.Help = true;
    }
    else if (arg == "-o" || arg == "--output")
    {
      o.Output = value();
    }
    else if (arg == "--report")
    {
      o.Report = true;
    }
    else if (arg == "--sweep")
    {
      const std::string text = value();
      o.ReportSettings.Sweep.clear();
      if (text != "none")
      {
        for (const double n : ParseNumberList(text, ',', arg, "N,N,... or none"))
        {
          if (n != static_cast<int>(n) || n < 3 || n > 4096)
          {
            BadOption("--sweep expects whole numbers from 3 to 4096");
          }
          o.ReportSettings.Sweep.push_back(static_cast<int>(n));
        }
      }
    }
    else if (arg == "--no-builtin")
    {
      o.ReportSettings.BuiltinMeshes = false;
    }
    else if (arg == "--repeats" || arg == "--reference-samples")
    {
      const double n = ParseNumbers(value(), ',', 1, arg, "a count")[0];
      if (n != static_cast<int>(n) || n < 1 || n > 4096)
      {
        BadOption(arg + " expects a whole number from 1 to 4096");
      }
      (arg == "--repeats" ? o.ReportSettings.Repeats : o.ReportSettings.ReferenceSamples) =
        static_cast<int>(n);
    }
    else if (arg == "-s" || arg == "--size")
    {
      o.SizeGiven = true;
      const std::string text = value();
      const auto wh = ParseNumbers(text, 'x', 2, "--size", "WIDTHxHEIGHT, e.g. 800x600");
      if (wh[0] != static_cast<int>(wh[0]) || wh[1] != static_cast<int>(wh[1]) || wh[0] < 1 ||
        wh[1] < 1 || wh[0] > 16384 || wh[1] > 16384)
      {
        BadOption("--size expects whole numbers from 1 to 16384, got '" + text + "'");
      }
      o.Width = static_cast<int>(wh[0]);
      o.Height = static_cast<int>(wh[1]);
    }
    else if (arg == "--azimuth")
    {
      o.Azimuth = ParseNumbers(value(), ',', 1, arg, "degrees")[0];
    }
    else if (arg == "--elevation")
    {
      o.Elevation = ParseNumbers(value(), ',', 1, arg, "degrees")[0];
    }
    else if (arg == "--zoom")
    {
      o.Zoom = ParseNumbers(value(), ',', 1, arg, "a factor > 0")[0];
      if (!(o.Zoom > 0))
      {
        BadOption("--zoom expects a factor > 0");
      }
    }
    else if (arg == "--parallel")
    {
      o.Parallel = true;
    }
    else if (arg == "-l" || arg == "--light")
    {
      o.Lights.push_back(ParseLight(value()));
    }
    else if (arg == "--ambient")
    {
      o.Ambient = ParseColor(value(), arg);
    }
    else if (arg == "--color")
    {
      o.Color = ParseColor(value(), arg);
    }
    else if (arg == "--color-by")
    {
      o.ColorBy = value();
    }
    else if (arg == "--range")
    {
      const auto r = ParseNumbers(value(), ',', 2, arg, "MIN,MAX");
      o.Range = std::array<double, 2>{ r[0], r[1] };
    }
    else if (arg == "--shading" || arg == "--interpolation")
    {
      const std::string mode = value();
      if (mode == "flat" || mode == "gouraud" || mode == "phong")
      {
        o.Interpolation = mode == "flat" ? VTK_FLAT : mode == "gouraud" ? VTK_GOURAUD : VTK_PHONG;
      }
      else
      {
        BadOption(arg + " expects flat, gouraud or phong, got '" + mode + "'");
      }
    }
    else if (arg == "--samples")
    {
      const double n = ParseNumbers(value(), ',', 1, arg, "1, 4 or 16")[0];
      if (n != 1 && n != 4 && n != 16)
      {
        BadOption("--samples expects 1, 4 or 16");
      }
      o.Samples = static_cast<int>(n);
    }
    else if (arg == "--max-error")
    {
      o.MaxError = ParseNumbers(value(), ',', 1, arg, "8-bit units")[0];
      if (!(o.MaxError > 0.0))
      {
        BadOption("--max-error expects a number > 0 (8-bit units)");
      }
    }
    else if (arg == "--background")
    {
      o.Background = ParseColor(value(), arg);
    }
    else if (arg == "--painter")
    {
      o.Painter = true;
    }
    else if (arg == "-t" || arg == "--threads")
    {
      const double n = ParseNumbers(value(), ',', 1, arg, "a count")[0];
      if (n != static_cast<int>(n) || n < 0 || n > 1024)
      {
        BadOption("--threads expects a whole number from 0 to 1024");
      }
      o.Threads = static_cast<int>(n);
    }
    else if (arg == "--explain")
    {
      o.Explain = true;
    }
    else if (arg == "--progress")
    {
      o.Progress = true;
    }
    else if (arg == "-q" || arg == "--quiet")
    {
      o.Quiet = true;
    }
    else if (!arg.empty() && arg[0] == '-')
    {
      BadOption("unknown option '" + arg + "'");
    }
    else
    {
      o.Inputs.push_back(arg);
    }
  }
  if (!o.Report && o.Inputs.size() > 1)
  {
    BadOption("one mesh at a time; got '" + o.Inputs[0] + "' and '" + o.Inputs[1] + "'");
  }
  if (!o.Report && !o.Inputs.empty())
  {
    o.Input = o.Inputs[0];
  }
  if (!o.Help && !o.Report && o.Input.empty())
  {
    BadOption("no mesh file given");
  }
  if (o.Report)
  {
    ReportOptions& r = o.ReportSettings;
    r.Width = o.SizeGiven ? o.Width : 1920;
    r.Height = o.SizeGiven ? o.Height : 1080;
    r.Threads = o.Threads.value_or(0);
    r.Prefix = o.Output.empty() ? "report" : o.Output;
    r.Progress = !o.Quiet && (o.Progress || isatty(fileno(stderr)));
  }
  if (o.Output.empty() && !o.Input.empty())
  {
    o.Output = std::filesystem::path(o.Input).stem().string() + ".png";
  }
  return o;
}

std::string FirstLine(std::string text);

// Prints a VTK object's warnings as single lines instead of VTK's log records.
class WarningPrinter
{
public:
  explicit WarningPrinter(vtkObject* object)
  {
    this->Callback->SetCallback([](vtkObject*, unsigned long, void*, void* data) {
      if (data)
      {
        std::fprintf(
          stderr, "facet-render: warning: %s\n", FirstLine(static_cast<const char*>(data)).c_str());
      }
    });
    object->AddObserver(vtkCommand::WarningEvent, this->Callback);
  }

private:
  vtkNew<vtkCallbackCommand> Callback;
};

// Collects the first error a VTK object reports, so it can be told in one line.
class ErrorCatcher
{
public:
  explicit ErrorCatcher(vtkObject* object)
  {
    this->Callback->SetClientData(this);
    this->Callback->SetCallback([](vtkObject*, unsigned long, void* self, void* data) {
      auto* catcher = static_cast<ErrorCatcher*>(self);
      if (catcher->Message.empty() && data)
      {
        catcher->Message = static_cast<const char*>(data);
      }
    });
    object->AddObserver(vtkCommand::ErrorEvent, this->Callback);
  }
  std::string Message;

private:
  vtkNew<vtkCallbackCommand> Callback;
};

// VTK's messages end with a "vtkClass (0x...): what happened" line; keep what happened.
std::string FirstLine(std::string text)
{
  while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
  {
    text.pop_back();
  }
  const auto lastLine = text.find_last_of('\n');
  std::string line = lastLine == std::string::npos ? text : text.substr(lastLine + 1);
  if (const auto header = line.find("): ");
      line.rfind("vtk", 0) == 0 && header != std::string::npos)
  {
    line = line.substr(header + 3);
  }
  return line;
}

template<class Reader>
vtkSmartPointer<vtkAlgorithm> MakeReader(const std::string& path)
{
  auto reader = vtkSmartPointer<Reader>::New();
  reader->SetFileName(path.c_str());
  return reader;
}

vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path)
{
  if (!std::filesystem::is_regular_file(path))
  {
    throw Failure("cannot read '" + path + "': no such file", false);
  }
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), ::tolower);
  vtkSmartPointer<vtkAlgorithm> reader;
  if (extension == ".vtp")
  {
    reader = MakeReader<vtkXMLPolyDataReader>(path);
  }
  else if (extension == ".vtk")
  {
    reader = MakeReader<vtkPolyDataReader>(path);
  }
  else if (extension == ".obj")
  {
    reader = MakeReader<vtkOBJReader>(path);
  }
  else if (extension == ".ply")
  {
    reader = MakeReader<vtkPLYReader>(path);
  }
  else if (extension == ".stl")
  {
    reader = MakeReader<vtkSTLReader>(path);
  }
  else
  {
    throw Failure(
      "cannot read '" + path + "': unknown extension (use .vtp .vtk .obj .ply or .stl)", true);
  }
  ErrorCatcher errors(reader);
  reader->Update();
  vtkSmartPointer<vtkPolyData> mesh = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  if (!errors.Message.empty())
  {
    throw Failure("cannot read '" + path + "': " + FirstLine(errors.Message), false);
  }
  if (!mesh || mesh->GetNumberOfCells() == 0)
  {
    throw Failure("cannot read '" + path + "': no polygons in it", false);
  }
  return mesh;
}

// The automatic camera's view turned by azimuth and elevation, fitted to the mesh as the
// filter fits it (so the clipping range suits the turned view), then zoomed.
vtkSmartPointer<vtkCamera> FitCamera(vtkPolyData* mesh, const Options& o)
{
  auto camera = vtkSmartPointer<vtkCamera>::New();
  camera->SetParallelProjection(o.Parallel);
  camera->Azimuth(o.Azimuth);
  camera->Elevation(o.Elevation);
  camera->OrthogonalizeViewUp();
  vtkFacetRenderFilter::ResetCamera(camera, mesh, o.Width, o.Height);
  camera->Zoom(o.Zoom);
  return camera;
}

vtkSmartPointer<vtkLight> MakeLight(const LightSpec& spec)
{
  auto light = vtkSmartPointer<vtkFacetLight>::New();
  light->SetColor(spec.Color.data());
  if (spec.Kind == "headlight")
  {
    light->SetLightTypeToHeadlight();
    return light;
  }
  light->SetLightTypeToSceneLight();
  if (spec.Kind == "directional")
  {
    light->SetPosition(0, 0, 0);
    light->SetFocalPoint(spec.Vector.data());
    return light;
  }
  light->SetPositional(true);
  light->SetPosition(spec.Vector.data());
  if (spec.Kind == "point")
  {
    light->SetConeAngle(180); // all around
  }
  else if (spec.Kind == "spot")
  {
    light->SetFocalPoint(spec.Focal.data());
    if (!spec.Cone.empty())
    {
      light->SetConeAngle(spec.Cone[0]);
    }
    if (spec.Cone.size() > 1)
    {
      light->SetExponent(spec.Cone[1]);
    }
  }
  else // linear-spot
  {
    light->SetFocalPoint(spec.Focal.data());
    light->SetSpotModelToLinearFalloff();
    if (!spec.Cone.empty())
    {
      light->SetFullIntensityAngle(spec.Cone[0]);
      light->SetFalloffAngle(spec.Cone[1]);
    }
  }
  return light;
}

void ColorBy(vtkFacetRenderFilter* render, vtkPolyData* mesh, const Options& o)
{
  vtkDataArray* array = mesh->GetPointData()->GetArray(o.ColorBy.c_str());
  const bool onPoints = array != nullptr;
  if (!array)
  {
    array = mesh->GetCellData()->GetArray(o.ColorBy.c_str());
  }
  if (!array)
  {
    throw Failure(
      "--color-by: '" + o.Input + "' has no point or cell array '" + o.ColorBy + "'", true);
  }
  render->SelectColorArray(o.ColorBy.c_str());
  if (onPoints)
  {
    render->SetScalarModeToUsePointFieldData();
  }
  else
  {
    render->SetScalarModeToUseCellFieldData();
  }
  render->SetColorModeToMapScalars();
  render->SetArrayComponent(array->GetNumberOfComponents() > 1 ? -1 : 0);
  double range[2];
  array->GetRange(range, array->GetNumberOfComponents() > 1 ? -1 : 0);
  if (o.Range)
  {
    range[0] = (*o.Range)[0];
    range[1] = (*o.Range)[1];
  }
  render->SetScalarRange(range);
}

// A progress bar on stderr, shown once a render has run for a quarter of a second.
struct ProgressBar
{
  std::chrono::steady_clock::time_point Start = std::chrono::steady_clock::now();
  bool Shown = false;

  static void OnProgress(vtkObject*, unsigned long, void* self, void* data)
  {
    auto* bar = static_cast<ProgressBar*>(self);
    const double fraction = *static_cast<double*>(data);
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - bar->Start).count();
    if (!bar->Shown && seconds < 0.25)
    {
      return;
    }
    bar->Shown = true;
    const int filled = static_cast<int>(fraction * 30.0);
    std::fprintf(stderr,
      "\rrendering [%.*s%*s] %3d%%",
      filled,
      "##############################",
      30 - filled,
      "",
      static_cast<int>(fraction * 100.0));
    std::fflush(stderr);
  }

  void Finish() const
  {
    if (this->Shown)
    {
      std::fprintf(stderr, "\n");
    }
  }
};

int Run(int argc, char** argv)
{
  const Options o = ParseOptions(argc, argv);
  if (o.Help)
  {
    std::fputs(UsageText().c_str(), stdout);
    return 0;
  }
  if (o.Report)
  {
    ReportOptions report = o.ReportSettings;
    for (const std::string& path : o.Inputs)
    {
      report.Meshes.emplace_back(std::filesystem::path(path).filename().string(), ReadMesh(path));
    }
    report.MeshFolder = FACET_REPORT_MESH_DIR;
    report.PlotScript = FACET_REPORT_PLOT_SCRIPT;
    report.Read = ReadMesh;
    try
    {
      return RunReport(report);
    }
    catch (const std::runtime_error& e)
    {
      throw Failure(std::string("report: ") + e.what(), false);
    }
  }
  vtkSmartPointer<vtkPolyData> mesh = ReadMesh(o.Input);

  vtkNew<vtkFacetRenderFilter> render;
  ErrorCatcher renderErrors(render);
  WarningPrinter renderWarnings(render);
  render->SetInputData(mesh);
  render->SetSize(o.Width, o.Height);
  render->SetBackground(o.Background.data());
  if (o.Ambient)
  {
    render->SetAmbientLightColor(o.Ambient->data());
  }
  if (o.Threads)
  {
    render->SetNumberOfThreads(*o.Threads);
  }
  render->SetCamera(FitCamera(mesh, o));
  render->GetProperty()->SetColor(o.Color[0], o.Color[1], o.Color[2]);
  render->GetProperty()->SetInterpolation(o.Interpolation);
  render->SetSamplesPerPixel(o.Samples);
  render->SetMaximumError(o.MaxError);
  // The filter estimates flat shading's error by default (EstimateError): the tool says it.
  if (o.Painter)
  {
    render->SetVisibilityModeToPainterSort();
  }
  for (const LightSpec& light : o.Lights)
  {
    render->AddLight(MakeLight(light));
  }
  if (o.ColorBy.empty())
  {
    render->ScalarVisibilityOff();
  }
  else
  {
    ColorBy(render, mesh, o);
  }

  ProgressBar bar;
  vtkNew<vtkCallbackCommand> progress;
  progress->SetClientData(&bar);
  progress->SetCallback(ProgressBar::OnProgress);
  if (!o.Quiet && (o.Progress || isatty(fileno(stderr))))
  {
    render->AddObserver(vtkCommand::ProgressEvent, progress);
  }
  render->Update();
  bar.Finish();
  if (!renderErrors.Message.empty())
  {
    throw Failure("cannot render '" + o.Input + "': " + FirstLine(renderErrors.Message), false);
  }

  vtkNew<vtkPNGWriter> writer;
  ErrorCatcher writeErrors(writer);
  writer->SetInputConnection(render->GetOutputPort());
  writer->SetFileName(o.Output.c_str());
  writer->Write();
  if (!writeErrors.Message.empty() || !std::filesystem::is_regular_file(o.Output))
  {
    throw Failure("cannot write '" + o.Output + "'" +
        (writeErrors.Message.empty() ? "" : ": " + FirstLine(writeErrors.Message)),
      false);
  }
  if (!o.Quiet)
  {
    vtkFieldData* fieldData = render->GetOutput()->GetFieldData();
    vtkDataArray* estimate = fieldData->GetArray("FacetErrorEstimate");
    std::printf("facet-render: wrote %s (%dx%d, %lld polygons, %.1f ms; flat shading's error "
                "here is at most %.1f RMS, %.0f max, in 8-bit units)\n",
      o.Output.c_str(),
      o.Width,
      o.Height,
      static_cast<long long>(mesh->GetNumberOfCells()),
      fieldData->GetArray("FacetRenderSeconds")->GetComponent(0, 0) * 1e3,
      estimate ? estimate->GetComponent(0, 0) : 0.0,
      estimate ? estimate->GetComponent(0, 1) : 0.0);
  }
  if (o.Explain)
  {
    std::fputs(render->GetRenderPlan(), stdout);
  }
  return 0;
}
}

int main(int argc, char** argv)
{
  // Errors and warnings are reported as single lines through observers; what VTK's
  // internal objects print (parsers, executives) goes nowhere.
  vtkNew<vtkStringOutputWindow> quiet;
  vtkOutputWindow::SetInstance(quiet);
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  try
  {
    return Run(argc, argv);
  }
  catch (const Failure& failure)
  {
    std::fprintf(stderr, "facet-render: %s\n", failure.what());
    return failure.Usage ? 2 : 1;
  }
}
