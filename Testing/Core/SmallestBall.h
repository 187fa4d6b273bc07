// The smallest ball enclosing points, computed for tests independently of CGAL: Welzl's
// incremental algorithm (each point outside the ball so far must lie on the boundary of the
// ball of the points before it), in double. For points in general position: three collinear or
// four coplanar points on a boundary give no unique circumsphere.
#ifndef atpTestSmallestBall_h
#define atpTestSmallestBall_h

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

namespace atp
{
namespace test
{

using Point = std::array<double, 3>;

struct Ball
{
  Point Center{ { 0, 0, 0 } };
  double Radius = -1; ///< negative: no point yet
};

inline double Distance(const Point& a, const Point& b)
{
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/// The ball whose boundary holds 1 to 4 points, of least radius among those.
inline Ball BallThrough(const std::vector<Point>& q)
{
  const auto sub = [](const Point& a, const Point& b) { return Point{ { a[0] - b[0], a[1] - b[1], a[2] - b[2] } }; };
  const auto dot = [](const Point& a, const Point& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  const auto cross = [](const Point& a, const Point& b) {
    return Point{ { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] } };
  };
  Ball ball;
  Point offset{ { 0, 0, 0 } }; // from q[0]
  if (q.size() == 2)
  {
    offset = sub(q[1], q[0]);
    for (double& x : offset)
    {
      x /= 2;
    }
  }
  else if (q.size() == 3)
  {
    const Point ab = sub(q[1], q[0]), ac = sub(q[2], q[0]);
    const Point n = cross(ab, ac);
    const Point u = cross(n, ab), w = cross(ac, n);
    const double scale = 2 * dot(n, n);
    for (int a = 0; a < 3; ++a)
    {
      offset[std::size_t(a)] = (dot(ac, ac) * u[std::size_t(a)] + dot(ab, ab) * w[std::size_t(a)]) / scale;
    }
  }
  else if (q.size() == 4)
  {
    // 2 (q[i] - q[0]) . offset = |q[i] - q[0]|^2, by Cramer's rule.
    const Point r1 = sub(q[1], q[0]), r2 = sub(q[2], q[0]), r3 = sub(q[3], q[0]);
    const double det = 2 * dot(r1, cross(r2, r3));
    const Point c23 = cross(r2, r3), c31 = cross(r3, r1), c12 = cross(r1, r2);
    for (int a = 0; a < 3; ++a)
    {
      const std::size_t i = std::size_t(a);
      offset[i] = (dot(r1, r1) * c23[i] + dot(r2, r2) * c31[i] + dot(r3, r3) * c12[i]) / det;
    }
  }
  for (int a = 0; a < 3; ++a)
  {
    ball.Center[std::size_t(a)] = q[0][std::size_t(a)] + offset[std::size_t(a)];
  }
  ball.Radius = 0;
  for (const Point& p : q)
  {
    ball.Radius = std::max(ball.Radius, Distance(ball.Center, p));
  }
  return ball;
}

/// The smallest ball holding `points` (shuffled first: expected linear time).
inline Ball SmallestBall(std::vector<Point> points)
{
  std::shuffle(points.begin(), points.end(), std::mt19937(1));
  const auto outside = [](const Ball& b, const Point& p) {
    return b.Radius < 0 || Distance(b.Center, p) > b.Radius * (1 + 1e-12);
  };
  Ball ball;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    if (!outside(ball, points[i]))
    {
      continue;
    }
    ball = BallThrough({ points[i] });
    for (std::size_t j = 0; j < i; ++j)
    {
      if (!outside(ball, points[j]))
      {
        continue;
      }
      ball = BallThrough({ points[i], points[j] });
      for (std::size_t k = 0; k < j; ++k)
      {
        if (!outside(ball, points[k]))
        {
          continue;
        }
        ball = BallThrough({ points[i], points[j], points[k] });
        for (std::size_t l = 0; l < k; ++l)
        {
          if (outside(ball, points[l]))
          {
            ball = BallThrough({ points[i], points[j], points[k], points[l] });
          }
        }
      }
    }
  }
  return ball;
}

} // namespace test
} // namespace atp

#endif
