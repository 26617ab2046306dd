#include "fitting/chain.h"

#include <Eigen/Dense>
#include <cmath>

#include "core/inflection_segment.h"
#include "core/three_point_segment.h"

namespace la {

const char* toString(PieceKind kind) {
  switch (kind) {
    case PieceKind::kThreePoint: return "three_point";
    case PieceKind::kInflectionStart: return "inflection_start";
    case PieceKind::kInflectionEnd: return "inflection_end";
  }
  return "unknown";
}

bool controlTriangle(const Chain& chain, std::size_t i, Vec2& q0, Vec2& q1, Vec2& q2) {
  q0 = chain.joints[i];
  q2 = chain.joints[i + 1];
  const Vec2 u = unitVector(chain.angles[i]), v = unitVector(chain.angles[i + 1]);
  const Vec2 chord = q2 - q0;
  const double det = cross(u, v);
  if (det == 0.0) {  // parallel tangents: fine only along the chord (a straight piece)
    q1 = 0.5 * (q0 + q2);
    return std::abs(cross(u, chord)) <= 1e-14 * chord.norm() && u.dot(chord) > 0.0;
  }
  // q0 + a u = q2 - b v
  const double a = cross(chord, v) / det, b = cross(u, chord) / det;
  q1 = q0 + a * u;
  return a > 0.0 && b > 0.0;
}

SegmentSolve solvePiece(const Chain& chain, std::size_t i) {
  Vec2 q0, q1, q2;
  if (!controlTriangle(chain, i, q0, q1, q2)) {
    SegmentSolve out;
    out.report.status = SolveStatus::kBadInput;
    out.report.message = "joint tangents do not form a control triangle";
    return out;
  }
  switch (chain.pieces[i].kind) {
    case PieceKind::kInflectionStart: return solveInflectionSegment(q0, q1, q2, InflectionEnd::kStart);
    case PieceKind::kInflectionEnd: return solveInflectionSegment(q0, q1, q2, InflectionEnd::kEnd);
    case PieceKind::kThreePoint: break;
  }
  return solveThreePointSegment(chain.pieces[i].alpha, q0, q1, q2);
}

}  // namespace la
