// Initial constrained Delaunay triangulation on the CPU with CGAL (exact predicates), then
// conversion to the engine's arrays. The only CGAL translation unit of the core.
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_plus_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/spatial_sort.h>

#include <unordered_set>

#include "refine2d/input.h"

namespace gdr::r2d {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
// Face info: its triangle number (no hash maps over 2M faces).
using Fb = CGAL::Constrained_triangulation_face_base_2<
    K, CGAL::Triangulation_face_base_with_info_2<int, K>>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;

long long key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<long long>(a) << 32) | static_cast<unsigned>(b);
}

// Inserts the points in spatial order (fast walks); vh[i] is point i's vertex.
template <class Tr>
void insert_points(Tr& tr, const std::vector<Point2>& pts,
                   std::vector<typename Tr::Vertex_handle>& vh) {
  const int n = static_cast<int>(pts.size());
  vh.assign(n, typename Tr::Vertex_handle());
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i) order[i] = i;
  struct Traits {
    const std::vector<Point2>* p;
    using Point_2 = int;
    struct Less_x_2 {
      const std::vector<Point2>* p;
      bool operator()(int a, int b) const { return (*p)[a].x < (*p)[b].x; }
    };
    struct Less_y_2 {
      const std::vector<Point2>* p;
      bool operator()(int a, int b) const { return (*p)[a].y < (*p)[b].y; }
    };
    Less_x_2 less_x_2_object() const { return Less_x_2{p}; }
    Less_y_2 less_y_2_object() const { return Less_y_2{p}; }
  };
  CGAL::spatial_sort(order.begin(), order.end(), Traits{&pts});
  typename Tr::Face_handle hint;
  for (int i : order) {
    auto v = tr.insert(K::Point_2(pts[i].x, pts[i].y), hint);
    v->info() = i;
    vh[i] = v;
    hint = v->face();
  }
}

}  // namespace

void split_segments_at_intersections(CleanPslg& g) {
  // CGAL's constrained triangulation with intersecting constraints (exact predicates): each
  // crossing becomes a vertex at the intersection point rounded to the nearest double, or
  // snapped to an endpoint within a few ulps of it (CGAL's rule), so that concurrent
  // segments share one vertex; a constraint through an existing vertex, collinear overlaps
  // and points on segments are split there. The constraint hierarchy gives each input
  // segment's chain of vertices. Constrained edges are triangulation edges, so the chains
  // cannot cross, overlap or pass through a vertex.
  struct Info {
    int id = -1;  // point index; -1 for a vertex CGAL created at an intersection
    Info& operator=(int i) {
      id = i;
      return *this;
    }
  };
  using Vb2 = CGAL::Triangulation_vertex_base_with_info_2<Info, K>;
  using Fb2 = CGAL::Constrained_triangulation_face_base_2<K>;
  using Tds2 = CGAL::Triangulation_data_structure_2<Vb2, Fb2>;
  using Cdt2 = CGAL::Constrained_Delaunay_triangulation_2<K, Tds2, CGAL::Exact_predicates_tag>;
  using Cdtp = CGAL::Constrained_triangulation_plus_2<Cdt2>;
  Cdtp cdt;
  std::vector<Cdtp::Vertex_handle> vh;
  insert_points(cdt, g.points, vh);
  std::vector<Cdtp::Constraint_id> cid(g.segments.size());
  for (std::size_t s = 0; s < g.segments.size(); ++s)
    cid[s] = cdt.insert_constraint(vh[g.segments[s][0]], vh[g.segments[s][1]]);
  // New vertices, numbered after the points in the order the chains meet them.
  auto index = [&](Cdtp::Vertex_handle v) {
    if (v->info().id < 0) {
      v->info().id = static_cast<int>(g.points.size());
      g.points.push_back(Point2{v->point().x(), v->point().y()});
    }
    return v->info().id;
  };
  std::vector<std::array<int, 2>> segs;
  std::vector<int> origin;
  std::unordered_set<long long> seen;
  for (std::size_t s = 0; s < g.segments.size(); ++s) {
    int prev = -1;
    for (auto it = cdt.vertices_in_constraint_begin(cid[s]);
         it != cdt.vertices_in_constraint_end(cid[s]); ++it) {
      const int v = index(*it);
      // An overlap is kept once, with the first segment that covers it.
      if (prev >= 0 && v != prev && seen.insert(key(prev, v)).second) {
        segs.push_back({prev, v});
        origin.push_back(g.segment_origin[s]);
      }
      prev = v;
    }
  }
  g.segments.swap(segs);
  g.segment_origin.swap(origin);
}

HostMesh initial_cdt(const CleanPslg& g, bool remove_exterior) {
  Cdt cdt;
  std::vector<Cdt::Vertex_handle> vh;
  insert_points(cdt, g.points, vh);
  for (const auto& s : g.segments) cdt.insert_constraint(vh[s[0]], vh[s[1]]);

  // Every finite face, numbered; the domain is cut out by assemble_cdt.
  CdtTriangles c;
  int nt = 0;
  for (auto f : cdt.finite_face_handles()) f->info() = nt++;
  c.tv.resize(3 * std::size_t(nt));
  c.tn.resize(3 * std::size_t(nt));
  c.tseg.assign(3 * std::size_t(nt), -1);
  for (auto f : cdt.finite_face_handles()) {
    const int t = f->info();
    for (int i = 0; i < 3; ++i) {
      // CGAL: vertices counter-clockwise, neighbour(i) opposite vertex(i) -- our convention.
      c.tv[3 * t + i] = f->vertex(i)->info();
      Cdt::Face_handle nb = f->neighbor(i);
      c.tn[3 * t + i] = cdt.is_infinite(nb) ? -1 : 3 * nb->info() + nb->index(f);
    }
  }
  // Each segment's edge, found around its first vertex (no table of 2M edges to hash).
  for (std::size_t s = 0; s < g.segments.size(); ++s) {
    Cdt::Face_handle f;
    int i;
    if (!cdt.is_edge(vh[g.segments[s][0]], vh[g.segments[s][1]], f, i)) continue;  // split: found below
    for (int side = 0; side < 2; ++side) {
      if (!cdt.is_infinite(f)) c.tseg[3 * f->info() + i] = static_cast<int>(s);
      const Cdt::Face_handle nb = f->neighbor(i);
      i = nb->index(f);
      f = nb;
    }
  }
  for (auto f : cdt.finite_face_handles()) {
    const int t = f->info();
    for (int i = 0; i < 3; ++i) {
      if (f->is_constrained(i) && c.tseg[3 * t + i] < 0) {
        // A constraint CGAL split at a point on it: not an edge of the input.
        // Numbered as in the input file (an intersection point has no number there).
        const int a = c.tv[3 * t + (i + 1) % 3], b = c.tv[3 * t + (i + 2) % 3];
        auto name = [&](int v) {
          const int o = g.point_origin[v];
          return o < 0 ? std::string("(an intersection point)") : std::to_string(o + g.first_index);
        };
        throw Error(Status::SelfIntersectingInput,
                    "a point lies on the interior of a segment near points " + name(a) + " and " + name(b) +
                        " (split the segment there, or leave strict input off)");
      }
      if (remove_exterior && !f->is_constrained(i) && c.tn[3 * t + i] < 0)
        c.exterior_seeds.push_back(t);  // reached from the infinite face
    }
  }
  auto face_at = [&](const Point2& p) {
    Cdt::Face_handle f = cdt.locate(K::Point_2(p.x, p.y));
    return f == Cdt::Face_handle() || cdt.is_infinite(f) ? -1 : f->info();
  };
  for (const auto& h : g.holes) c.hole_tris.push_back(face_at(h));
  for (const auto& r : g.regions) c.region_tris.push_back(face_at(r.point));
  return assemble_cdt(g, std::move(c));
}

std::vector<double> interpolate_over_cdt(const CleanPslg& g, const std::vector<double>& values,
                                         int count, const std::vector<Point2>& queries) {
  Cdt cdt;
  std::vector<Cdt::Vertex_handle> vh;
  insert_points(cdt, g.points, vh);
  for (const auto& s : g.segments) cdt.insert_constraint(vh[s[0]], vh[s[1]]);
  std::vector<double> out(queries.size() * count, 0.0);
  Cdt::Face_handle hint;
  for (std::size_t q = 0; q < queries.size(); ++q) {
    const K::Point_2 p(queries[q].x, queries[q].y);
    Cdt::Face_handle f = cdt.locate(p, hint);
    if (f == Cdt::Face_handle()) continue;
    if (cdt.is_infinite(f)) {  // a point rounded just outside the hull: its finite neighbour
      const int i = f->index(cdt.infinite_vertex());
      f = f->neighbor(i);
    }
    hint = f;
    // Barycentric coordinates (a point rounded just outside extrapolates by as little).
    const K::Point_2 &a = f->vertex(0)->point(), &b = f->vertex(1)->point(),
                     &c = f->vertex(2)->point();
    const double area = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
    const double w[3] = {
        ((b.x() - p.x()) * (c.y() - p.y()) - (b.y() - p.y()) * (c.x() - p.x())) / area,
        ((c.x() - p.x()) * (a.y() - p.y()) - (c.y() - p.y()) * (a.x() - p.x())) / area,
        ((a.x() - p.x()) * (b.y() - p.y()) - (a.y() - p.y()) * (b.x() - p.x())) / area};
    for (int k = 0; k < 3; ++k) {
      const int v = f->vertex(k)->info();
      for (int j = 0; j < count; ++j) out[q * count + j] += w[k] * values[std::size_t(v) * count + j];
    }
  }
  return out;
}

}  // namespace gdr::r2d
