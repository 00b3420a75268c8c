// Initial constrained Delaunay triangulation on the CPU with CGAL (exact predicates), then
// conversion to the engine's arrays. The only CGAL translation unit of the core.
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/spatial_sort.h>

#include <unordered_map>

#include "refine2d/input.h"

namespace gdr::r2d {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
// Face info: its triangle number, or kOutside / kUnset (no hash maps over 2M faces).
enum : int { kUnset = -1, kOutside = -2 };
using Fb = CGAL::Constrained_triangulation_face_base_2<
    K, CGAL::Triangulation_face_base_with_info_2<int, K>>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;

long long key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<long long>(a) << 32) | static_cast<unsigned>(b);
}

}  // namespace

HostMesh initial_cdt(const CleanPslg& g, bool remove_exterior) {
  const int n = static_cast<int>(g.points.size());
  Cdt cdt;
  std::vector<Cdt::Vertex_handle> vh(n);
  {
    // Insert in spatial order (fast walks), remembering each vertex's index.
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
    CGAL::spatial_sort(order.begin(), order.end(), Traits{&g.points});
    Cdt::Face_handle hint;
    for (int i : order) {
      Cdt::Vertex_handle v = cdt.insert(K::Point_2(g.points[i].x, g.points[i].y), hint);
      v->info() = i;
      vh[i] = v;
      hint = v->face();
    }
  }
  std::unordered_map<long long, int> seg_of;
  seg_of.reserve(g.segments.size() * 2);
  for (std::size_t s = 0; s < g.segments.size(); ++s) {
    cdt.insert_constraint(vh[g.segments[s][0]], vh[g.segments[s][1]]);
    seg_of[key(g.segments[s][0], g.segments[s][1])] = static_cast<int>(s);
  }

  // Domain: everything (convex hull), or only what is enclosed by segments and not in a
  // hole: flood from the hull and from each hole seed without crossing a constraint.
  for (auto f : cdt.all_face_handles()) f->info() = kUnset;
  if (remove_exterior || !g.holes.empty()) {
    std::vector<Cdt::Face_handle> stack;
    if (remove_exterior)
      for (auto f : cdt.all_face_handles())
        if (cdt.is_infinite(f)) stack.push_back(f);
    for (const auto& h : g.holes) {
      Cdt::Face_handle f = cdt.locate(K::Point_2(h.x, h.y));
      if (f != Cdt::Face_handle() && !cdt.is_infinite(f)) stack.push_back(f);
    }
    while (!stack.empty()) {
      Cdt::Face_handle f = stack.back();
      stack.pop_back();
      if (f->info() == kOutside) continue;
      f->info() = kOutside;
      for (int i = 0; i < 3; ++i)
        if (!f->is_constrained(i) && f->neighbor(i)->info() != kOutside)
          stack.push_back(f->neighbor(i));
    }
  }
  std::vector<Cdt::Face_handle> faces;
  for (auto f : cdt.finite_face_handles()) {
    if (f->info() == kOutside) continue;
    f->info() = static_cast<int>(faces.size());
    faces.push_back(f);
  }
  if (faces.empty())
    throw Error(Status::InvalidInput,
                "no triangles are left after removing the exterior and the holes (are the "
                "boundary segments closed, and are the hole points inside them?)");

  HostMesh m;
  m.xy.resize(2 * std::size_t(n));
  for (int i = 0; i < n; ++i) {
    m.xy[2 * i] = g.points[i].x;
    m.xy[2 * i + 1] = g.points[i].y;
  }
  m.ptype.assign(n, kInputPoint);
  m.pseg.assign(n, -1);
  for (const auto& s : g.segments) m.seg.insert(m.seg.end(), {s[0], s[1]});
  m.input_segments = static_cast<int>(g.segments.size());
  const std::size_t nt = faces.size();
  m.tv.resize(3 * nt);
  m.tn.resize(3 * nt);
  m.ts.resize(3 * nt);
  for (std::size_t t = 0; t < nt; ++t) {
    Cdt::Face_handle f = faces[t];
    for (int i = 0; i < 3; ++i) {
      // CGAL: vertices counter-clockwise, neighbour(i) opposite vertex(i) -- our convention.
      m.tv[3 * t + i] = f->vertex(i)->info();
      Cdt::Face_handle nb = f->neighbor(i);
      const int id = cdt.is_infinite(nb) ? kOutside : nb->info();
      m.tn[3 * t + i] = id < 0 ? -1 : 3 * id + nb->index(f);
    }
  }
  // Segment of each edge; domain-boundary edges that are not segments become hull segments.
  for (std::size_t t = 0; t < nt; ++t) {
    Cdt::Face_handle f = faces[t];
    for (int i = 0; i < 3; ++i) {
      const int a = m.tv[3 * t + (i + 1) % 3], b = m.tv[3 * t + (i + 2) % 3];
      int s = -1;
      if (f->is_constrained(i)) {
        auto it = seg_of.find(key(a, b));
        if (it == seg_of.end())
          throw Error(Status::SelfIntersectingInput,
                      "a point lies on the interior of a segment near points " +
                          std::to_string(a) + " and " + std::to_string(b) +
                          " (split the segment there, or use the split-intersections option)");
        s = it->second;
      } else if (m.tn[3 * t + i] < 0) {
        s = static_cast<int>(m.seg.size() / 2);
        m.seg.insert(m.seg.end(), {a, b});
      }
      m.ts[3 * t + i] = s;
    }
  }
  return m;
}

}  // namespace gdr::r2d
