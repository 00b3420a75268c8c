// `gdr selfcheck`: build configuration, CUDA device, and a small meshing + validation run on
// each available backend, plus an output round trip. Exit 1 when anything fails.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "args.h"
#include "build_info.h"
#include "cli.h"
#include "gdr/backend.h"
#include "gdr/io.h"
#include "gdr/refine2d.h"
#include "gdr/validate.h"
#include "mesh_attributes.h"
#include "table.h"

namespace gdr::cli {

namespace {

// The kernel's transparent huge page mode (the bracketed word of its setting): "madvise" or
// "always" give the pages gdr asks for, "never" none.
std::string huge_page_mode() {
  std::FILE* f = std::fopen("/sys/kernel/mm/transparent_hugepage/enabled", "r");
  if (!f) return "unknown";
  char line[128] = {};
  const bool read = std::fgets(line, sizeof line, f) != nullptr;
  std::fclose(f);
  const std::string s = read ? line : "";
  const std::size_t a = s.find('['), b = s.find(']');
  return a != std::string::npos && b != std::string::npos && b > a ? s.substr(a + 1, b - a - 1) : "unknown";
}

const char* kHelpSelfcheck = R"(gdr selfcheck - check that this build works on this machine

Usage:
  gdr selfcheck

Prints the build configuration and the CUDA device, meshes a small built-in input (a unit
square with a square hole, minimum angle 25 degrees, area bound) on the CPU and, when a GPU
is usable, on the GPU; validates each mesh (conformity, constrained Delaunay, quality, the
hole's area) and writes and reads back a mesh file. Exit code 0 when all checks pass, 1 when
one fails.
)";

constexpr double kAngle = 25.0;
constexpr double kMaxArea = 0.005;
constexpr double kExpectedArea = 1.0 - 0.2 * 0.2;

Pslg square_with_hole() {
  Pslg p;
  p.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.4, 0.4}, {0.6, 0.4}, {0.6, 0.6}, {0.4, 0.6}};
  p.segments = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}};
  p.holes = {{0.5, 0.5}};
  return p;
}

Refine2dOptions selfcheck_options(Backend backend) {
  Refine2dOptions o;
  o.min_angle = kAngle;
  o.max_area = kMaxArea;
  o.remove_exterior = true;
  o.backend = backend;
  return o;
}

// Meshes and validates on one backend; returns an empty string on success, else the reason.
std::string check_backend(Backend backend, std::string& detail, TriMesh* mesh_out) {
  const Pslg input = square_with_hole();
  const auto t0 = std::chrono::steady_clock::now();
  Refine2dResult r;
  try {
    r = refine_2d(input, selfcheck_options(backend));
  } catch (const Error& e) {
    return std::string(to_string(e.status())) + ": " + e.what();
  }
  const double secs =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ValidateOptions vo;
  vo.min_angle_deg = kAngle;
  const ValidationReport rep = validate_trimesh(r.mesh, &input, vo);
  const QualityStats& q = rep.quality;
  double max_area = 0;
  for (const auto& t : r.mesh.triangles)
    max_area = std::max(max_area, triangle_area(r.mesh.points[t[0]], r.mesh.points[t[1]],
                                                r.mesh.points[t[2]]));
  detail = with_commas(static_cast<long long>(r.mesh.points.size())) + " points, " +
           with_commas(static_cast<long long>(r.mesh.triangles.size())) + " triangles, " +
           with_commas(r.stats.steiner_points) + " Steiner, min angle " +
           fixed(q.min_angle_deg, 2) + " deg, " + seconds(secs);
  if (r.stats.backend_used != backend)
    return std::string("ran on ") + to_string(r.stats.backend_used) + " instead of " +
           to_string(backend);
  if (!rep.valid) return "invalid mesh: " + rep.summary();
  if (q.bad_elements != 0)
    return std::to_string(q.bad_elements) + " triangles below " + fixed(kAngle, 0) + " deg";
  if (std::abs(q.total_measure - kExpectedArea) > 1e-9)
    return "area " + fixed(q.total_measure, 12) + " instead of " + fixed(kExpectedArea, 12) +
           " (hole or exterior not honoured)";
  if (max_area > kMaxArea * (1 + 1e-9))
    return "a triangle of area " + fixed(max_area, 6) + " exceeds the bound " + fixed(kMaxArea, 6);
  if (mesh_out) *mesh_out = std::move(r.mesh);
  return "";
}

// Writes the mesh as .vtu, .vtp and Triangle files into a temporary folder and reads the
// .node back.
std::string check_io(const TriMesh& mesh, std::string& detail) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path dir = fs::temp_directory_path(ec) / ("gdr-selfcheck-" + std::to_string(::getpid()));
  if (ec) return "no temporary folder: " + ec.message();
  fs::create_directories(dir, ec);
  if (ec) return dir.string() + ": " + ec.message();
  std::string failure;
  try {
    const io::Attributes attributes = triangle_attributes(mesh, kAngle);
    io::write_mesh((dir / "square.vtu").string(), mesh, attributes);
    io::write_mesh((dir / "square.vtp").string(), mesh, attributes);
    io::write_mesh((dir / "square.node").string(), mesh);
    const Pslg back = io::read_poly((dir / "square.node").string());
    if (back.points.size() != mesh.points.size())
      failure = "read back " + std::to_string(back.points.size()) + " points of " +
                std::to_string(mesh.points.size());
    detail = ".vtu, .vtp, .node/.ele written; .node read back";
  } catch (const Error& e) {
    failure = std::string(to_string(e.status())) + ": " + e.what();
  }
  fs::remove_all(dir, ec);
  return failure;
}

}  // namespace

int run_selfcheck(const std::vector<std::string>& args) {
  bool help = false;
  const auto positional = parse_options(
      "selfcheck", args, {{"help", 'h', false, [&](const std::string&) { help = true; }}});
  if (help) {
    std::fputs(kHelpSelfcheck, stdout);
    return kExitOk;
  }
  if (!positional.empty())
    throw UsageError("selfcheck", "unexpected argument '" + positional[0] + "'");

  const DeviceInfo& dev = device_info();
  std::printf("gdr %s self-check\n", version());
  std::printf("  build        %s\n", build_summary().c_str());
  const auto env = [](const char* name) -> std::string {
    const char* v = std::getenv(name);
    return v && *v ? std::string(name) + "=" + v : std::string();
  };
  std::string waiting = env("OMP_WAIT_POLICY");
  if (waiting.empty()) waiting = env("GOMP_SPINCOUNT");
  if (waiting.empty()) waiting = "OpenMP's default";
  std::printf("  CPU backend  OpenMP, %d threads, waiting %s\n", cpu_threads(), waiting.c_str());
  const std::string tunables = env("GLIBC_TUNABLES");
  std::printf("  host memory  %s, transparent huge pages %s\n",
              tunables.empty() ? "glibc's default pages" : tunables.c_str(), huge_page_mode().c_str());
  if (dev.available)
    std::printf("  CUDA device  %s, %s\n", dev.name.c_str(), bytes(dev.total_memory).c_str());
  else
    std::printf("  CUDA device  none (%s)\n", dev.reason.c_str());
  std::fflush(stdout);

  int failures = 0;
  auto report = [&](const char* what, const std::string& failure, const std::string& detail) {
    if (failure.empty()) {
      std::printf("  [ok]    %-9s %s\n", what, detail.c_str());
    } else {
      std::printf("  [FAIL]  %-9s %s%s%s\n", what, failure.c_str(), detail.empty() ? "" : " | ",
                  detail.c_str());
      ++failures;
    }
    std::fflush(stdout);
  };

  std::string detail;
  TriMesh mesh;
  report("cpu mesh", check_backend(Backend::Cpu, detail, &mesh), detail);
  if (dev.available) {
    detail.clear();
    report("gpu mesh", check_backend(Backend::Gpu, detail, nullptr), detail);
  } else {
    std::printf("  [skip]  %-9s no usable GPU\n", "gpu mesh");
  }
  detail.clear();
  if (!mesh.triangles.empty())
    report("io", check_io(mesh, detail), detail);
  else
    std::printf("  [skip]  %-9s no CPU mesh to write\n", "io");

  if (failures == 0)
    std::printf("self-check passed\n");
  else
    std::printf("self-check FAILED (%d failed)\n", failures);
  return failures == 0 ? kExitOk : kExitInvalidMesh;
}

}  // namespace gdr::cli
