// One switch over the predicates, shared by the CPU tests and the GPU kernel.
#pragma once
#include "predicates/predicates.h"

namespace gdr::test {

enum class Pred { Orient2d, Incircle, Orient3d, Insphere, DiametralCircle, DiametralSphere };

constexpr int kNumPreds = 6;

GDR_HD_INLINE int pred_points(Pred p) {
  switch (p) {
    case Pred::Orient2d: return 3;
    case Pred::Incircle: return 4;
    case Pred::Orient3d: return 4;
    case Pred::Insphere: return 5;
    default: return 3;
  }
}

GDR_HD_INLINE int pred_dim(Pred p) {
  return (p == Pred::Orient2d || p == Pred::Incircle || p == Pred::DiametralCircle) ? 2 : 3;
}

GDR_HD_INLINE bool has_sos(Pred p) { return p != Pred::DiametralCircle && p != Pred::DiametralSphere; }

GDR_HD_INLINE int sign_of(double v) { return (v > 0.0) - (v < 0.0); }

// Sign of predicate p on points q[0..]; *stage receives the deciding stage.
GDR_HD_INLINE int eval_sign(Pred p, const double* const* q, int* stage) {
  switch (p) {
    case Pred::Orient2d: return sign_of(pred::orient2d(q[0], q[1], q[2], stage));
    case Pred::Incircle: return sign_of(pred::incircle(q[0], q[1], q[2], q[3], stage));
    case Pred::Orient3d: return sign_of(pred::orient3d(q[0], q[1], q[2], q[3], stage));
    case Pred::Insphere: return sign_of(pred::insphere(q[0], q[1], q[2], q[3], q[4], stage));
    case Pred::DiametralCircle: return pred::in_diametral_circle(q[0], q[1], q[2], stage);
    default: return pred::in_diametral_sphere(q[0], q[1], q[2], stage);
  }
}

GDR_HD_INLINE int eval_sos(Pred p, const double* const* q, const int* i) {
  switch (p) {
    case Pred::Orient2d: return pred::orient2d_sos(q[0], q[1], q[2], i[0], i[1], i[2]);
    case Pred::Incircle: return pred::incircle_sos(q[0], q[1], q[2], q[3], i[0], i[1], i[2], i[3]);
    case Pred::Orient3d: return pred::orient3d_sos(q[0], q[1], q[2], q[3], i[0], i[1], i[2], i[3]);
    case Pred::Insphere:
      return pred::insphere_sos(q[0], q[1], q[2], q[3], q[4], i[0], i[1], i[2], i[3], i[4]);
    default: return 0;
  }
}

}  // namespace gdr::test
