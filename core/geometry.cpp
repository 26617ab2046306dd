#include "core/geometry.h"

#include <Eigen/Eigenvalues>

namespace la {

FittedLine leastSquaresLine(const std::vector<Vec2>& points) {
  if (points.empty()) return {};
  Vec2 centroid = Vec2::Zero();
  for (const Vec2& q : points) centroid += q;
  centroid /= static_cast<double>(points.size());
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const Vec2& q : points) scatter += (q - centroid) * (q - centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(scatter);
  const Vec2 normal = eigen.eigenvectors().col(0);  // smallest eigenvalue first
  double deviation = 0.0;
  for (const Vec2& q : points) deviation = std::max(deviation, std::abs((q - centroid).dot(normal)));
  return {centroid, Vec2(-normal.y(), normal.x()), deviation};
}

double lineDeviation(const std::vector<Vec2>& points) { return points.size() < 2 ? 0.0 : leastSquaresLine(points).deviation; }

}  // namespace la
