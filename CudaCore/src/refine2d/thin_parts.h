// Thin parts (issue 9): where two segments (or convex-hull edges) that share no endpoint run
// side by side at a width w, every triangle between them whose angles are all at least theta
// has an area of at most w^2 / tan(theta), so a strip of length L needs at least about
// L tan(theta) / w of them (a 1 x 1e-4 rectangle takes 0.31, 0.72 and 1.23 times L / w
// triangles at 10, 20 and 33 degrees: 1.8-1.9 tan(theta) L / w). Small input angles do not
// count: segments that meet at a vertex never make a pair, so what the small-angle rule leaves
// bad is not asked for. Rays go from 8 points of each subsegment of the CDT along its inward
// normal to the first subsegment they meet (at most 64 triangles away); where that one shares
// no endpoint with the first, the stretch of the ray's eighth that both cover counts, at the
// larger of the two widths at its ends (the width is linear along it). Each strip is seen
// from both sides, each side counting a quarter of tan(theta) L / w: a lower bound about 4
// times below what refinement makes, so that only what certainly cannot be meshed is refused.
//
// Only strips thinner than a width limit count (thin_width_limit): a ray stops once it is
// farther from its subsegment than that, so most walks end in the first triangle or two
// (walks to the far side of every region cost 0.1 s of a 0.3 s run on the counties map).
//
// Per triangle, on the host (refine2d.cpp) or where the CDT was assembled (cdt_assembly.h).
#pragma once
#include <cfloat>
#include <cmath>

#include "exec/hd.h"

namespace gdr::r2d {

struct ThinEstimate {
  double triangles = 0;  // at least this many triangles in thin parts
  double width = 0;      // the thinnest part's width and its length, scaled units
  double length = 0;
};

// What triangle t's segment edges add: `credit` (triangles asked for) and the largest single
// credit `best` with its strip's width and length.
struct ThinAt {
  double credit = 0, best = 0, width = 0, length = 0;
};

// The width beyond which strips are not counted when the estimate only has to tell whether
// more than `max_points` points are needed (2 triangles each). A sample of a subsegment of
// length len credits at most (len / 8) tan(theta) / (4 w), so all strips at least w wide
// together credit at most L tan(theta) / (2 w), L the length of every segment and hull edge
// (each seen from two sides): at this limit, 1% of what a refusal needs. 0: no limit.
inline double thin_width_limit(double total_length, double tan_theta, double max_points) {
  return max_points > 0 && total_length > 0 ? 25.0 * total_length * tan_theta / max_points : 0.0;
}

// tv, tn, ts: the CDT (mesh2d.h, ts the segment on each edge or -1); seg: 2 per segment;
// max_width: thin_width_limit (0: none).
GDR_HD inline ThinAt thin_parts_at(int t, const int* tv, const int* tn, const int* ts,
                                   const int* seg, const double* xy, double tan_theta, double max_width) {
  constexpr int kSamples = 8, kMaxSteps = 64;
  ThinAt r;
  for (int e = 0; e < 3; ++e) {
    const int s = ts[3 * t + e];
    if (s < 0) continue;
    const double* a = xy + 2 * tv[3 * t + (e + 1) % 3];
    const double* b = xy + 2 * tv[3 * t + (e + 2) % 3];
    const double ux = b[0] - a[0], uy = b[1] - a[1], len = sqrt(ux * ux + uy * uy);
    if (!(len > 0)) continue;
    const double nx = -uy / len, ny = ux / len;  // inward: the triangle is counter-clockwise
    for (int i = 0; i < kSamples; ++i) {
      const double f = (i + 0.5) / kSamples;
      const double o[2] = {a[0] + f * ux, a[1] + f * uy};
      int u = t, entry = e, hit = -1;
      for (int step = 0; step < kMaxSteps && hit < 0; ++step) {
        int exit = -1;
        double h = 0;  // the ray's height where it leaves
        for (int j = 0; j < 3; ++j) {
          if (j == entry) continue;
          const double* p = xy + 2 * tv[3 * u + (j + 1) % 3];
          const double* q = xy + 2 * tv[3 * u + (j + 2) % 3];
          // Sides of p and q across the ray's line; the ray leaves through the edge whose
          // endpoints lie on both sides of it.
          const double sp = (p[0] - o[0]) * ny - (p[1] - o[1]) * nx;
          const double sq = (q[0] - o[0]) * ny - (q[1] - o[1]) * nx;
          if ((sp <= 0 && sq >= 0) || (sp >= 0 && sq <= 0)) {
            exit = j;
            const double hp = (p[0] - o[0]) * nx + (p[1] - o[1]) * ny;
            const double hq = (q[0] - o[0]) * nx + (q[1] - o[1]) * ny;
            h = sp == sq ? fmin(hp, hq) : (hp * sq - hq * sp) / (sq - sp);
            break;
          }
        }
        if (exit < 0 || (max_width > 0 && h > max_width)) break;  // beyond the limit: stop
        if (ts[3 * u + exit] >= 0) {
          hit = ts[3 * u + exit];
          break;
        }
        const int nb = tn[3 * u + exit];
        if (nb < 0) break;
        u = nb / 3;
        entry = nb % 3;
      }
      if (hit < 0) continue;
      const int sa = seg[2 * s], sb = seg[2 * s + 1], ha = seg[2 * hit], hb = seg[2 * hit + 1];
      if (s == hit || sa == ha || sa == hb || sb == ha || sb == hb) continue;  // incident
      // The other segment's endpoints in the frame of ab: along it (in units of len) and
      // their heights over it.
      const double* c = xy + 2 * ha;
      const double* d = xy + 2 * hb;
      const double tc = ((c[0] - a[0]) * ux + (c[1] - a[1]) * uy) / (len * len);
      const double td = ((d[0] - a[0]) * ux + (d[1] - a[1]) * uy) / (len * len);
      const double hc = (c[0] - a[0]) * nx + (c[1] - a[1]) * ny;
      const double hd = (d[0] - a[0]) * nx + (d[1] - a[1]) * ny;
      if (!(fabs(td - tc) > 0)) continue;  // perpendicular to ab: no strip
      const double u0 = fmax(double(i) / kSamples, fmin(tc, td));
      const double u1 = fmin(double(i + 1) / kSamples, fmax(tc, td));
      if (!(u1 > u0)) continue;
      const double g0 = hc + (hd - hc) * (u0 - tc) / (td - tc);
      const double g1 = hc + (hd - hc) * (u1 - tc) / (td - tc);
      const double w = fmax(g0, g1);
      if (!(w > 0 && w <= DBL_MAX)) continue;  // finite and positive
      const double credit = (u1 - u0) * len * tan_theta / (4.0 * w);
      r.credit += credit;
      if (credit > r.best) {
        r.best = credit;
        r.width = w;
        r.length = (fmin(1.0, fmax(tc, td)) - fmax(0.0, fmin(tc, td))) * len;
      }
    }
  }
  return r;
}

}  // namespace gdr::r2d
