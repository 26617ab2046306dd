#pragma once
// A chain of LA segments described by what the G2 solve moves: joint positions stay
// fixed, the tangent angle at every joint is free, and each segment is rebuilt from
// its control triangle (the two joints and the intersection of their tangents) with
// its own alpha, or with alpha solved when one end is an inflection (seed 003 3.2-3.3).

#include <vector>

#include "core/segment_solve.h"

namespace la {

enum class PieceKind { kThreePoint, kInflectionStart, kInflectionEnd };
const char* toString(PieceKind kind);

struct ChainPiece {
  PieceKind kind = PieceKind::kThreePoint;
  double alpha = -1.0;  // used by kThreePoint; an inflection piece solves its own (read it off its segment)
};

struct Chain {
  std::vector<Vec2> joints;       // n + 1 points for n pieces (closed: the last equals the first)
  std::vector<double> angles;     // tangent angle at each joint (same count as joints)
  std::vector<ChainPiece> pieces;
  bool closed = false;            // the last joint is the first: its angle is shared
  /// Joints whose tangent angle the user fixed (by dragging a control triangle's apex):
  /// empty, or one flag per joint. Such a joint slides along its tangent line instead,
  /// which keeps the apex where the user put it.
  std::vector<bool> sliding;
  bool slides(std::size_t joint) const { return !sliding.empty() && sliding[joint]; }
  std::size_t size() const { return pieces.size(); }
};

/// The control triangle of piece i from the joint tangents: Q1 is where the tangent
/// lines meet. Returns false if they do not meet ahead of Q0 and behind Q2.
bool controlTriangle(const Chain& chain, std::size_t i, Vec2& q0, Vec2& q1, Vec2& q2);

/// Builds piece i's LA segment (alpha solved for inflection pieces).
SegmentSolve solvePiece(const Chain& chain, std::size_t i);

}  // namespace la
