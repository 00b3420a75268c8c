// `gdr rdt`: surface and volume meshing by restricted Delaunay refinement (gDP3d).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "args.h"
#include "cli.h"
#include "command_support.h"
#include "gdr/backend.h"
#include "gdr/io.h"
#include "gdr/rdt3d.h"
#include "gdr/validate.h"
#include "interrupt.h"
#include "json_writer.h"
#include "progress_bar.h"
#include "table.h"

namespace gdr::cli {

namespace {

const char* kHelpRdt = R"(gdr rdt - surface and volume mesh approximating a surface (restricted Delaunay)

Usage:
  gdr rdt INPUT -o OUTPUT [options]

INPUT is a triangulated surface: .off, .stl (ASCII or binary), .ply, .obj. It may be
coarse, fine or badly shaped: it is resampled with well-shaped triangles of the chosen
size (3D restricted Delaunay refinement, as CGAL Mesh_3 does), whose vertices lie on it.
A closed surface (one or several shells; a shell inside another bounds a cavity) gives
tetrahedra inside it and the surface around them; an open surface, or --surface-only,
gives the surface alone. Non-manifold or self-intersecting surfaces are refused with the
edges or faces named. OUTPUT is written by its extension:
  .vtu   the tetrahedra (cell arrays RadiusEdgeRatio, MinDihedralAngle, MaxDihedralAngle,
         Volume, IsBad; point array PointType: 0 corner, 1 on a feature edge, 3 on the
         surface, 2 inside),
         and the surface beside it as NAME_surface.vtp (cell arrays MinAngle, Size,
         Distance, IsBad)
  .mesh  Medit: tetrahedra and surface triangles
  .vtp   the surface alone (what --surface-only writes; also for open surfaces)
  .off   the surface alone, points and triangles
Without -o the mesh is computed, summarized and (with --check) validated, but not written.

Criteria (CGAL Mesh_3's names; sizes default to fractions of the bounding box diagonal D):
  --facet-angle DEG        smallest angle of a surface triangle (default 30, at most 30)
  --facet-size S           radius of a surface triangle's surface Delaunay ball (default D/20)
  --facet-distance D       distance from a surface triangle's circumcentre to the input
                           surface (default D/500)
  --cell-radius-edge B     largest circumradius-to-shortest-edge ratio of a tetrahedron
                           (default 2; at least 1; 0 turns it off)
  --cell-size S            largest circumradius of a tetrahedron (default: the facet size)
  A size of 0 turns that criterion off.
  --sliver-angle DEG       after refinement, move interior points to raise dihedral angles
                           below DEG (and above 180 - DEG), keeping --cell-radius-edge and
                           --cell-size, as gdr tet --sliver-angle does (default off; at most
                           30). Only points whose tetrahedra all lie inside move: the
                           surface and the volume stay exactly as they were. The mesh is
                           then not Delaunay where points moved, and --check skips that test
  --feature-angle DEG      keep sharp features: input edges whose triangles' normals differ
                           by more than DEG (and the boundary of an open surface) are kept
                           as chains of surface edges, their corners as vertices (default 0:
                           none; 30 suits CAD parts). Next to features at small angles, the
                           triangles and tetrahedra that cannot meet the criteria are left
                           and counted as bad; where the surface cuts across a sharp edge
                           (at corners, and at acute creases sampled unevenly on its two
                           sides) the subsegments off it are counted and warned about
  --surface-only           mesh the surface only, even when it is closed
  --no-manifold            do not refine where the surface is not a 2-manifold (CGAL's
                           non_manifold()). By default, once the criteria are met, the
                           triangles at edges and vertices where the surface pinches (a
                           part thinner than the triangles) are refined until it is a
                           manifold, down to triangles of D/1000 or 1/8 of the facet size;
                           pinches left there (rough input: a scan's noise) are undone by
                           moving tetrahedra with all corners on the surface to the other
                           side; what is left is counted and warned about
  --max-steiner N          stop cleanly after inserting N points (default: no cap where
                           refinement terminates; an automatic cap below --cell-radius-edge 2)
Algorithm:
  --backend auto|gpu|cpu   where to refine (default auto: GPU for large inputs when present)
Checking and reporting:
  --check                  validate the result: the surface a closed, oriented 2-manifold
                           without self-intersections (for a closed input), the tetrahedra
                           positive with the surface as their boundary, the whole Delaunay
                           triangulation Delaunay (exact insphere; skipped when
                           --sliver-angle moved points), every sharp feature a chain of
                           surface edges; exit code 1 when invalid
  --stats-json FILE        write the options, statistics, histograms and validation as JSON
  --histogram FILE.csv     write the dihedral-angle histogram of the tetrahedra (all six
                           angles of every tetrahedron, 1-degree bins): angle_lo,angle_hi,count
  -q, --quiet              no progress, warnings or summary; errors only
  -h, --help               this text

Examples:
  gdr rdt scan.off -o scan.vtu --facet-size 0.5 --facet-distance 0.05 --check
  gdr rdt open_scan.ply -o open_scan.vtp
  gdr rdt part.stl -o part.mesh --cell-radius-edge 3
  gdr rdt scan.off -o scan.vtu --sliver-angle 15 --check
  gdr rdt cad_part.off -o cad_part.vtu --feature-angle 30 --check

Exit codes: 0 ok, 1 invalid mesh (--check), 2 usage error (also: an output that would
overwrite an input), 3 input error, 4 device error, 5 internal error, 130 interrupted.
)";

struct ArgsRdt {
  std::string input, output, stats_json, histogram;
  RestrictedDelaunayOptions options;
  bool check = false, quiet = false, help = false;
};

std::string extension(const std::string& path) { return std::filesystem::path(path).extension().string(); }

bool surface_output(const std::string& path) {
  const std::string ext = extension(path);
  return ext == ".vtp" || ext == ".off";
}

// BASE_surface.vtp beside BASE.vtu.
std::string surface_beside(const std::string& vtu) {
  const std::filesystem::path p(vtu);
  return (p.parent_path() / (p.stem().string() + "_surface.vtp")).string();
}

ArgsRdt parse_rdt(const std::vector<std::string>& args) {
  const std::string cmd = "rdt";
  ArgsRdt a;
  auto number = [&](const char* name, double& dst) {
    return OptionSpec{name, 0, true, [&, name](const std::string& v) {
                        dst = parse_number(cmd, name, v);
                        if (dst < 0) throw UsageError(cmd, std::string("--") + name + " must be >= 0");
                      }};
  };
  const std::vector<OptionSpec> specs = {
      {"output", 'o', true, [&](const std::string& v) { a.output = v; }},
      number("facet-angle", a.options.facet_angle),
      number("facet-size", a.options.facet_size),
      number("facet-distance", a.options.facet_distance),
      number("cell-radius-edge", a.options.cell_radius_edge_ratio),
      number("cell-size", a.options.cell_size),
      number("feature-angle", a.options.feature_angle),
      number("sliver-angle", a.options.sliver_angle),
      {"surface-only", 0, false, [&](const std::string&) { a.options.mesh_volume = false; }},
      {"no-manifold", 0, false, [&](const std::string&) { a.options.manifold = false; }},
      {"max-steiner", 0, true,
       [&](const std::string& v) {
         a.options.max_steiner_points = parse_integer(cmd, "max-steiner", v);
         if (a.options.max_steiner_points < 0) throw UsageError(cmd, "--max-steiner must be >= 0");
       }},
      {"backend", 0, true, [&](const std::string& v) { a.options.backend = parse_backend(cmd, v); }},
      {"check", 0, false, [&](const std::string&) { a.check = true; }},
      {"stats-json", 0, true, [&](const std::string& v) { a.stats_json = v; }},
      {"histogram", 0, true, [&](const std::string& v) { a.histogram = v; }},
      {"quiet", 'q', false, [&](const std::string&) { a.quiet = true; }},
      {"help", 'h', false, [&](const std::string&) { a.help = true; }},
  };
  const auto positional = parse_options(cmd, args, specs);
  if (a.help) return a;
  a.input = single_input(cmd, positional);
  if (!a.output.empty()) {
    const std::string ext = extension(a.output);
    if (ext != ".vtu" && ext != ".mesh" && !surface_output(a.output))
      throw UsageError(cmd, "cannot tell the output format of '" + a.output + "': use .vtu, .mesh, .vtp or .off");
    if (!a.options.mesh_volume && !surface_output(a.output))
      throw UsageError(cmd, "--surface-only writes a surface: use .vtp or .off for -o");
  }
  if (!a.histogram.empty() && !a.options.mesh_volume)
    throw UsageError(cmd, "--histogram counts the dihedral angles of tetrahedra: not with --surface-only");
  if (a.options.facet_angle > 30)
    throw UsageError(cmd, "--facet-angle must be at most 30 (above, refinement need not terminate)");
  if (a.options.feature_angle >= 180) throw UsageError(cmd, "--feature-angle must be below 180");
  if (a.options.sliver_angle > 30) throw UsageError(cmd, "--sliver-angle must be at most 30");
  if (a.options.sliver_angle > 0 && !a.options.mesh_volume)
    throw UsageError(cmd, "--sliver-angle improves tetrahedra: not with --surface-only");
  return a;
}

std::vector<OutputFile> outputs_of(const ArgsRdt& a) {
  std::vector<OutputFile> out;
  if (!a.output.empty()) {
    out.push_back({a.output, "-o " + a.output});
    if (extension(a.output) == ".vtu") out.push_back({surface_beside(a.output), "-o " + a.output});
  }
  if (!a.stats_json.empty()) out.push_back({a.stats_json, "--stats-json " + a.stats_json});
  if (!a.histogram.empty()) out.push_back({a.histogram, "--histogram " + a.histogram});
  return out;
}

// One cell array, in single precision where the mesher measured it so.
template <class Values>
void add_cell_array(io::Attributes& at, const char* name, const Values& values, bool float32) {
  at.cell_data.push_back({name, 1, std::vector<double>(values.begin(), values.end()), float32});
}

io::Attributes tet_arrays(const RestrictedDelaunayResult& r) {
  io::Attributes at;
  add_cell_array(at, "RadiusEdgeRatio", r.radius_edge, true);
  add_cell_array(at, "MinDihedralAngle", r.min_dihedral, true);
  add_cell_array(at, "MaxDihedralAngle", r.max_dihedral, true);
  add_cell_array(at, "Volume", r.volume, false);
  add_cell_array(at, "IsBad", r.is_bad, true);
  return at;
}

io::Attributes surface_arrays(const RestrictedDelaunayResult& r) {
  io::Attributes at;
  add_cell_array(at, "MinAngle", r.facet_min_angle, true);
  add_cell_array(at, "Size", r.facet_size, false);
  add_cell_array(at, "Distance", r.facet_distance, false);
  add_cell_array(at, "IsBad", r.facet_is_bad, true);
  return at;
}

void write_outputs(const ArgsRdt& a, const RestrictedDelaunayResult& r) {
  make_parent_dirs(a.output);
  const std::string ext = extension(a.output);
  if (surface_output(a.output)) {
    io::write_surface(a.output, r.mesh, surface_arrays(r));
  } else if (ext == ".mesh") {
    io::write_mesh(a.output, r.mesh);
  } else {
    io::write_surface(surface_beside(a.output), r.mesh, surface_arrays(r));
    io::write_mesh(a.output, r.mesh, tet_arrays(r));
  }
}

struct Reports {
  ValidationReport surface, features, tets, triangulation;
  // With tetrahedra: their volume, and the volume the surface encloses (the same up to
  // rounding when the surface bounds them, smoothed or not).
  double tet_volume = 0, enclosed_volume = 0;
  bool volume_agrees = true;
  bool valid() const {
    return surface.valid && features.valid && tets.valid && triangulation.valid && volume_agrees;
  }
};

// The volume the surface triangles enclose (signed: positive for outward triangles), from a
// point of the surface; `scale` gets the sum of the terms' magnitudes (what rounding is
// relative to).
double enclosed_volume(const TetMesh& m, double& scale) {
  double v = 0;
  scale = 0;
  if (m.subfaces.empty()) return 0;
  const Point3 o = m.points[m.subfaces[0][0]];
  for (const auto& t : m.subfaces) {
    const Point3 &pa = m.points[t[0]], &pb = m.points[t[1]], &pc = m.points[t[2]];
    const Point3 a{pa.x - o.x, pa.y - o.y, pa.z - o.z}, b{pb.x - o.x, pb.y - o.y, pb.z - o.z},
        c{pc.x - o.x, pc.y - o.y, pc.z - o.z};
    const double term = a.x * (b.y * c.z - b.z * c.y) - a.y * (b.x * c.z - b.z * c.x) + a.z * (b.x * c.y - b.y * c.x);
    v += term;
    scale += std::abs(term);
  }
  scale /= 6;
  return v / 6;
}

// Whether --check tests the Delaunay property: not where sliver smoothing moved points.
bool delaunay_checked(const RestrictedDelaunayResult& r) { return r.stats.sliver_moves == 0; }

Reports check_mesh(const RestrictedDelaunayResult& r) {
  Reports rep;
  rep.surface = validate_surface(r.mesh.points, r.mesh.subfaces, r.stats.closed_input);
  rep.features = validate_surface_features(r.mesh.points, r.mesh.subfaces, r.mesh.subsegments, r.features);
  ValidateOptions vo;
  vo.check_conformity = false;
  vo.check_delaunay = delaunay_checked(r);
  if (r.stats.volume_meshed) {
    rep.tets = validate_tetmesh(r.mesh, nullptr, vo);
    rep.tet_volume = rep.tets.quality.total_measure;
    double scale = 0;
    rep.enclosed_volume = enclosed_volume(r.mesh, scale);
    rep.volume_agrees = std::abs(rep.tet_volume - rep.enclosed_volume) <= 1e-9 * std::max(scale, rep.tet_volume);
  }
  rep.triangulation = validate_tetmesh(r.triangulation, nullptr, vo);
  return rep;
}

void print_summary(const ArgsRdt& a, const RestrictedDelaunayResult& r, const Reports* rep, const CliTimes& t) {
  const RestrictedDelaunayStats& s = r.stats;
  Table info(Table::Align::Left);
  info.row({"gdr rdt summary"});
  info.row({"input", a.input + ": " + with_commas(s.input_points) + " points, " +
                         with_commas(s.input_triangles) + " triangles, " +
                         (s.closed_input ? "closed" : "open")});
  info.row({"criteria", "facet angle " + fixed(s.facet_angle, 1) + " deg, size " + fixed(s.facet_size, 6) +
                            ", distance " + fixed(s.facet_distance, 6) + "; cell radius-edge " +
                            fixed(s.cell_radius_edge_ratio, 2) + ", size " + fixed(s.cell_size, 6)});
  info.row({"output", (a.output.empty() ? std::string("(not written)") : a.output) + ": " +
                          with_commas(s.output_points) + " points, " + with_commas(s.output_triangles) +
                          " surface triangles, " + with_commas(s.output_tets) + " tetrahedra"});
  info.row({"points inserted", with_commas(s.steiner_points) + " (" + with_commas(s.initial_points) +
                                   " initial) in " + std::to_string(s.iterations) + " iterations"});
  if (s.feature_edges > 0)
    info.row({"features", with_commas(s.feature_edges) + " input edges, " + with_commas(s.corners) + " corners (feature angle " +
                              fixed(s.feature_angle, 1) + " deg); " + with_commas(s.feature_points) +
                              " output points on them" +
                              (s.feature_relabelled > 0 ? "; " + with_commas(s.feature_relabelled) +
                                                              " tetrahedra changed side to keep them"
                                                        : std::string()) +
                              (s.features_off_surface > 0
                                   ? "; " + with_commas(s.features_off_surface) + " subsegments off the surface"
                                   : std::string())});
  if (s.steiner_cap_reached) info.row({"", "stopped at the cap of " + with_commas(s.steiner_cap)});
  if (s.stalled) info.row({"", "stalled: bad elements remain that no point could fix"});
  if (s.manifold_splits > 0 || s.non_manifold_facets > 0 || s.pinch_relabelled > 0)
    info.row({"manifold", with_commas(s.manifold_splits) + " triangles refined where the surface pinched" +
                              (s.pinch_relabelled > 0 ? ", " + with_commas(s.pinch_relabelled) +
                                                            " tetrahedra changed side at pinches left"
                                                      : std::string()) +
                              "; " +
                              (s.non_manifold_facets > 0 ? with_commas(s.non_manifold_facets) + " still at non-manifold places"
                                                         : std::string("now a manifold"))});
  info.row({"backend", backend_line(s.backend_used, s.device_name)});
  info.row({"surface", "min angle " + fixed(s.min_facet_angle_deg, 2) + " deg, max size " +
                           fixed(s.max_facet_size, 6) + ", max distance " + fixed(s.max_facet_distance, 6) +
                           ", area " + fixed(s.area, 6) + ", " + with_commas(s.bad_facets) + " bad"});
  if (s.volume_meshed)
    info.row({"tetrahedra", "dihedral " + fixed(s.min_dihedral_deg, 2) + ".." + fixed(s.max_dihedral_deg, 2) +
                                " deg, max radius-edge " + fixed(s.max_radius_edge, 3) + ", volume " +
                                fixed(s.volume, 6) + ", " + with_commas(s.bad_tets) + " bad"});
  if (s.sliver_angle > 0)
    info.row({"slivers", sliver_summary(s.sliver_angle, s.slivers_before, s.slivers_after, s.sliver_moves)});
  if (rep) {
    info.row({"check surface", (rep->surface.valid ? "valid: " : "INVALID: ") + rep->surface.summary()});
    if (s.feature_edges > 0)
      info.row({"check features", (rep->features.valid ? "valid: " : "INVALID: ") +
                                       with_commas(static_cast<long long>(r.mesh.subsegments.size())) +
                                       " subsegments, " + std::to_string(rep->features.missing_segments) +
                                       " features not kept, " + std::to_string(rep->features.invalid_subsegments) +
                                       " subsegments not on the surface"});
    if (s.volume_meshed) {
      info.row({"check tetrahedra", (rep->tets.valid ? "valid: " : "INVALID: ") + rep->tets.summary()});
      info.row({"check volume", std::string(rep->volume_agrees ? "valid: " : "INVALID: ") + "tetrahedra " +
                                    fixed(rep->tet_volume, 9) + ", enclosed by the surface " +
                                    fixed(rep->enclosed_volume, 9)});
    }
    const std::string whole = with_commas(static_cast<long long>(r.triangulation.tets.size())) +
                              " tetrahedra of the whole triangulation, ";
    if (delaunay_checked(r))
      info.row({"check Delaunay", (rep->triangulation.valid ? "valid: " : "INVALID: ") + whole +
                                      std::to_string(rep->triangulation.non_delaunay) +
                                      " faces not locally Delaunay"});
    else
      info.row({"check Delaunay", "skipped (sliver smoothing moved " + with_commas(s.sliver_moves) +
                                      " points): " + (rep->triangulation.valid ? "valid: " : "INVALID: ") +
                                      whole + "positive and manifold"});
  }
  info.print(std::cout);
  Table times;
  times.row({"time", "seconds"});
  times.row({"  input checks", fixed(s.input_seconds, 3)});
  times.row({"  initial triangulation", fixed(s.initial_seconds, 3)});
  times.row({"  refinement", fixed(s.refine_seconds, 3)});
  for (const auto& p : s.phases) times.row({"    " + p.name, fixed(p.seconds, 3)});
  times.row({"  output mesh", fixed(s.output_seconds, 3)});
  times.row({"  read input", fixed(t.read, 3)});
  if (!a.output.empty()) times.row({"  write output", fixed(t.write, 3)});
  if (rep) times.row({"  check", fixed(t.check, 3)});
  times.row({"  wall clock", fixed(t.wall, 3)});
  times.print(std::cout);
  if (s.volume_meshed) print_dihedral_histogram(std::cout, r.dihedral_histogram);
  std::cout.flush();
}

void write_stats_json(const ArgsRdt& a, const RestrictedDelaunayResult& r, const Reports* rep, const CliTimes& t) {
  std::ostringstream out;
  const RestrictedDelaunayStats& s = r.stats;
  JsonWriter j(out);
  j.begin_object();
  j.field("tool", "gdr rdt");
  j.field("input", a.input);
  j.field("output", a.output);
  j.key("options");
  j.begin_object();
  j.field("facet_angle", s.facet_angle);
  j.field("facet_size", s.facet_size);
  j.field("facet_distance", s.facet_distance);
  j.field("cell_radius_edge_ratio", s.cell_radius_edge_ratio);
  j.field("cell_size", s.cell_size);
  j.field("feature_angle", s.feature_angle);
  j.field("sliver_angle", a.options.sliver_angle);
  j.field("mesh_volume", a.options.mesh_volume);
  j.field("max_steiner_points", a.options.max_steiner_points);
  j.field("backend", to_string(a.options.backend));
  j.end_object();
  j.key("stats");
  j.begin_object();
  j.field("backend_used", to_string(s.backend_used));
  j.field("device_name", s.device_name);
  j.field("closed_input", s.closed_input);
  j.field("volume_meshed", s.volume_meshed);
  j.field("iterations", s.iterations);
  j.field("input_points", s.input_points);
  j.field("input_triangles", s.input_triangles);
  j.field("initial_points", s.initial_points);
  j.field("feature_edges", s.feature_edges);
  j.field("corners", s.corners);
  j.field("feature_points", s.feature_points);
  j.field("feature_min_length", s.feature_min_length);
  j.field("steiner_points", s.steiner_points);
  j.field("triangulation_points", s.triangulation_points);
  j.field("triangulation_tets", s.triangulation_tets);
  j.field("output_points", s.output_points);
  j.field("output_triangles", s.output_triangles);
  j.field("output_tets", s.output_tets);
  j.field("bad_facets", s.bad_facets);
  j.field("bad_tets", s.bad_tets);
  j.field("steiner_cap", s.steiner_cap);
  j.field("steiner_cap_reached", s.steiner_cap_reached);
  j.field("stalled", s.stalled);
  j.field("facets_left_out", s.facets_left_out);
  j.field("manifold_splits", s.manifold_splits);
  j.field("non_manifold_facets", s.non_manifold_facets);
  j.field("pinch_relabelled", s.pinch_relabelled);
  j.field("features_off_surface", s.features_off_surface);
  j.field("feature_relabelled", s.feature_relabelled);
  j.field("manifold_min_size", s.manifold_min_size);
  j.field("min_facet_angle_deg", s.min_facet_angle_deg);
  j.field("max_facet_size", s.max_facet_size);
  j.field("max_facet_distance", s.max_facet_distance);
  j.field("min_dihedral_deg", s.min_dihedral_deg);
  j.field("max_dihedral_deg", s.max_dihedral_deg);
  j.field("max_radius_edge", s.max_radius_edge);
  j.field("slivers_before", s.slivers_before);
  j.field("slivers_after", s.slivers_after);
  j.field("sliver_moves", s.sliver_moves);
  j.field("area", s.area);
  j.field("volume", s.volume);
  j.field("input_seconds", s.input_seconds);
  j.field("initial_seconds", s.initial_seconds);
  j.field("refine_seconds", s.refine_seconds);
  j.field("output_seconds", s.output_seconds);
  j.field("total_seconds", s.total_seconds);
  j.field("peak_device_bytes", static_cast<unsigned long long>(s.peak_device_bytes));
  j.phases_field("phases", s.phases);
  j.end_object();
  j.array_field("dihedral_histogram", r.dihedral_histogram);  // 1-degree bins over [0, 180)
  // Smallest angle per surface triangle, 1-degree bins over [0, 60].
  j.array_field("facet_angle_histogram", r.facet_angle_histogram);
  j.key("cli_seconds");
  j.begin_object();
  j.field("read", t.read);
  j.field("write", t.write);
  j.field("check", t.check);
  j.field("wall", t.wall);
  j.end_object();
  j.key("validation");
  if (!rep) {
    j.null();
  } else {
    j.begin_object();
    j.field("valid", rep->valid());
    j.field("surface", rep->surface.summary());
    j.field("features", rep->features.summary());
    j.field("tetrahedra", s.volume_meshed ? rep->tets.summary() : std::string());
    j.field("volume_agrees", rep->volume_agrees);
    j.field("delaunay_checked", delaunay_checked(r));
    j.field("non_delaunay", static_cast<unsigned long long>(rep->triangulation.non_delaunay));
    j.end_object();
  }
  j.end_object();
  make_parent_dirs(a.stats_json);
  io::write_file_atomically(a.stats_json, out.str());
}

Surface read_input(const std::string& path) {
  if (!std::filesystem::exists(path)) throw Error(Status::IoError, path + ": no such file");
  if (io::detect_input_kind(path) != io::InputKind::Surface3d)
    throw Error(Status::InvalidInput, path + ": is a 2D planar straight-line graph; 'gdr rdt' needs a 3D surface");
  return io::read_surface(path);
}

int mesh_rdt(const ArgsRdt& a, bool& written) {
  const auto t_start = std::chrono::steady_clock::now();
  CliTimes t;
  ProgressBar bar(!a.quiet);
  bar.update(-1, "reading " + a.input);
  auto t0 = std::chrono::steady_clock::now();
  const Surface input = read_input(a.input);
  t.read = since(t0);
  stop_if_interrupted();

  Callbacks callbacks;
  callbacks.progress = [&bar](double f, const std::string& phase) { bar.update(f, phase); };
  if (!a.quiet) callbacks.warning = [&bar](const std::string& m) { bar.message("gdr: warning: " + m); };
  callbacks.abort = [] { return InterruptHandler::received() != 0; };
  RestrictedDelaunayOptions options = a.options;
  options.keep_triangulation = a.check;
  const RestrictedDelaunayResult result = restricted_delaunay_3d(input, options, callbacks);
  stop_if_interrupted();
  if (!a.output.empty() && !surface_output(a.output) && !result.stats.volume_meshed)
    throw Error(Status::InvalidInput, "the surface is open: only a surface can be written; use .vtp or .off for -o");

  if (!a.output.empty()) {
    bar.update(-1, "writing " + a.output);
    t0 = std::chrono::steady_clock::now();
    write_outputs(a, result);
    written = true;
    t.write = since(t0);
    stop_if_interrupted();
  }
  Reports reports;
  if (a.check) {
    bar.update(-1, "checking the mesh");
    t0 = std::chrono::steady_clock::now();
    reports = check_mesh(result);
    t.check = since(t0);
  }
  t.wall = since(t_start);
  bar.finish();
  const Reports* rep = a.check ? &reports : nullptr;
  if (!a.stats_json.empty()) write_stats_json(a, result, rep, t);
  if (!a.histogram.empty()) {
    make_parent_dirs(a.histogram);
    write_dihedral_histogram_csv(a.histogram, result.dihedral_histogram);
  }
  if (!a.quiet) print_summary(a, result, rep, t);
  if (a.check && !reports.valid()) {
    std::fprintf(stderr, "gdr: error: the mesh is invalid\n");
    for (const ValidationReport* r : {&reports.surface, &reports.tets, &reports.triangulation})
      for (const auto& p : r->problems) std::fprintf(stderr, "  %s\n", p.c_str());
    if (!reports.volume_agrees)
      std::fprintf(stderr, "  the tetrahedra's volume %.17g is not the volume the surface encloses, %.17g\n",
                   reports.tet_volume, reports.enclosed_volume);
    return kExitInvalidMesh;
  }
  return kExitOk;
}

}  // namespace

int run_rdt(const std::vector<std::string>& args) {
  const ArgsRdt a = parse_rdt(args);
  if (a.help) {
    std::fputs(kHelpRdt, stdout);
    return kExitOk;
  }
  refuse_overwrites("rdt", a.input, io::surface_input_files(a.input), outputs_of(a));
  return run_interruptible(a.output, [&a](bool& written) { return mesh_rdt(a, written); });
}

}  // namespace gdr::cli
