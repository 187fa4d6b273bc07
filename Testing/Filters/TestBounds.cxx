// Bounding volumes of patches: the tight sphere is the smallest ball (checked against an
// independent Welzl), the saturated sphere holds its spheres, storage in floats only grows them,
// and cones of normals hold every face normal and every cone they were made of.
#include "atpBounds.h"
#include "FaceNormal.h"
#include "SmallestBall.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace
{
using atp::test::Point;

double DistanceTo(const atp::Sphere& s, const Point& p)
{
  return atp::test::Distance(Point{ { s.Center[0], s.Center[1], s.Center[2] } }, p);
}

using atp::test::AngleBetween;

double HalfAngle(const atp::NormalCone& cone)
{
  return atp::test::AngleOfCosine(cone.Cos);
}

/// An n x n grid of bumps of the given height, as a patch.
atp::PatchMesh Bumps(int n, double height)
{
  atp::PatchMesh mesh;
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= n; ++i)
    {
      const double x = double(i) / n, y = double(j) / n;
      mesh.Positions.insert(mesh.Positions.end(),
        { float(x), float(y), float(height * std::sin(7 * x) * std::cos(5 * y)) });
    }
  }
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      const std::uint32_t a = std::uint32_t(j * (n + 1) + i), b = a + 1, c = a + std::uint32_t(n) + 1, d = c + 1;
      mesh.Indices.insert(mesh.Indices.end(), { a, b, d, a, d, c });
    }
  }
  return mesh;
}

/// Every face normal of the patch; degenerate faces left out.
std::vector<Point> FaceNormals(const atp::PatchMesh& mesh)
{
  std::vector<Point> normals;
  for (std::size_t t = 0; t < mesh.TriangleCount(); ++t)
  {
    const Point n = atp::test::FaceNormal(mesh, t);
    if (!atp::test::IsZero(n))
    {
      normals.push_back(n);
    }
  }
  return normals;
}

} // namespace

TEST(Bounds, TightSphereIsTheSmallestBall)
{
  std::mt19937 random(7);
  for (int trial = 0; trial < 60; ++trial)
  {
    const double offset = trial % 3 == 0 ? 1e4 : 0, extent = trial % 2 ? 1e-2 : 5;
    std::uniform_real_distribution<double> coordinate(-extent, extent);
    const std::size_t count = 1 + std::size_t(trial) * 7;
    std::vector<float> positions;
    std::vector<Point> points;
    for (std::size_t i = 0; i < count; ++i)
    {
      float p[3];
      for (float& x : p)
      {
        x = float(offset + coordinate(random));
      }
      positions.insert(positions.end(), p, p + 3);
      points.push_back(Point{ { p[0], p[1], p[2] } });
    }
    const atp::Sphere sphere = atp::EnclosingSphere(positions.data(), count);
    const atp::test::Ball smallest = atp::test::SmallestBall(points);
    const double rounding = 1e-12 * (offset + extent);
    for (const Point& p : points)
    {
      ASSERT_LE(DistanceTo(sphere, p), sphere.Radius) << "trial " << trial << ": a point outside";
    }
    EXPECT_LE(sphere.Radius, smallest.Radius * (1 + 1e-9) + rounding) << "trial " << trial << ": not the smallest";
    EXPECT_GE(sphere.Radius, smallest.Radius * (1 - 1e-9) - rounding) << "trial " << trial;
  }
}

TEST(Bounds, TightSphereOfDegenerateSets)
{
  EXPECT_TRUE(atp::EnclosingSphere(nullptr, 0).IsEmpty());
  const float one[3] = { 1, 2, 3 };
  const atp::Sphere point = atp::EnclosingSphere(one, 1);
  EXPECT_EQ(point.Radius, 0);
  EXPECT_EQ(point.Center[2], 3);
  // Collinear, and coplanar on a circle: the ball of the farthest pair, the circle's ball.
  const float line[12] = { 0, 0, 0, 1, 1, 1, 3, 3, 3, 2, 2, 2 };
  EXPECT_NEAR(atp::EnclosingSphere(line, 4).Radius, std::sqrt(27.0) / 2, 1e-9);
  std::vector<float> circle;
  for (int k = 0; k < 12; ++k)
  {
    circle.insert(circle.end(), { float(2 * std::cos(k * M_PI / 6)), float(2 * std::sin(k * M_PI / 6)), 0.f });
  }
  EXPECT_NEAR(atp::EnclosingSphere(circle.data(), 12).Radius, 2, 1e-6);
}

TEST(Bounds, SaturatedSphereHoldsItsSpheresAndIsSmallest)
{
  std::mt19937 random(9);
  std::uniform_real_distribution<double> coordinate(-10, 10), size(0, 3);
  for (int trial = 0; trial < 100; ++trial)
  {
    std::vector<atp::Sphere> spheres(std::size_t(1 + trial % 9));
    std::vector<Point> centers;
    // Equal radii (every other trial): the smallest ball is that of the centers, grown by it.
    const double common = size(random);
    for (atp::Sphere& s : spheres)
    {
      for (double& x : s.Center)
      {
        x = coordinate(random);
      }
      s.Radius = trial % 2 ? common : size(random);
      centers.push_back(Point{ { s.Center[0], s.Center[1], s.Center[2] } });
    }
    spheres.push_back(atp::Sphere()); // empty: ignored
    const atp::Sphere outer = atp::EnclosingSphere(spheres);
    for (const atp::Sphere& s : spheres)
    {
      if (!s.IsEmpty())
      {
        ASSERT_LE(DistanceTo(outer, Point{ { s.Center[0], s.Center[1], s.Center[2] } }) + s.Radius, outer.Radius);
      }
    }
    if (trial % 2)
    {
      EXPECT_NEAR(outer.Radius, atp::test::SmallestBall(centers).Radius + common, 1e-9) << "trial " << trial;
    }
  }
  EXPECT_TRUE(atp::EnclosingSphere(std::vector<atp::Sphere>(3)).IsEmpty());
}

TEST(Bounds, StoredSpheresOnlyGrow)
{
  std::mt19937 random(13);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int trial = 0; trial < 1000; ++trial)
  {
    atp::Sphere s;
    const double scale = std::pow(10.0, trial % 8 - 2);
    for (double& x : s.Center)
    {
      x = unit(random) * scale * 100;
    }
    s.Radius = std::abs(unit(random)) * scale * (trial % 5 == 0 ? 1e-6 : 1);
    float stored[4];
    atp::StoreSphere(s, stored);
    const atp::Sphere loaded = atp::LoadSphere(stored);
    ASSERT_LE(DistanceTo(loaded, Point{ { s.Center[0], s.Center[1], s.Center[2] } }) + s.Radius, loaded.Radius)
      << "trial " << trial;
  }
  float empty[4];
  atp::StoreSphere(atp::Sphere(), empty);
  EXPECT_EQ(empty[3], 0);
  EXPECT_TRUE(atp::LoadSphere(empty).IsEmpty());
  // A point at the origin still stores with a radius, so it never reads back as empty.
  float point[4];
  atp::Sphere origin;
  origin.Radius = 0;
  atp::StoreSphere(origin, point);
  EXPECT_GT(point[3], 0);
  EXPECT_FALSE(atp::LoadSphere(point).IsEmpty());
}

TEST(Bounds, NormalConeHoldsEveryFaceNormal)
{
  for (const double height : { 0.0, 0.01, 0.1, 0.3, 2.0 })
  {
    const atp::PatchMesh patch = Bumps(24, height);
    const atp::NormalCone cone = atp::FaceNormalCone(patch);
    ASSERT_FALSE(cone.Empty);
    double widest = 0;
    for (const Point& n : FaceNormals(patch))
    {
      const double angle = AngleBetween(cone.Axis, n.data());
      EXPECT_LE(angle, HalfAngle(cone) + 1e-12) << "height " << height;
      widest = std::max(widest, angle);
    }
    // Tight about its axis: no wider than the widest normal from it.
    EXPECT_LE(HalfAngle(cone), widest + 1e-12) << "height " << height;
    if (height == 0)
    {
      EXPECT_GE(cone.Cos, 1 - 1e-12) << "a flat patch faces one way";
    }
  }
  // A closed surface faces every way; degenerate faces have no normal.
  atp::PatchMesh tetrahedron;
  tetrahedron.Positions = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  tetrahedron.Indices = { 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3 };
  EXPECT_EQ(atp::FaceNormalCone(tetrahedron).Cos, -1);
  atp::PatchMesh flat;
  flat.Positions = { 0, 0, 0, 1, 0, 0, 2, 0, 0 };
  flat.Indices = { 0, 1, 2 };
  EXPECT_TRUE(atp::FaceNormalCone(flat).Empty);
}

TEST(Bounds, EnclosingConeHoldsItsConesAndStoringOnlyWidens)
{
  std::mt19937 random(17);
  std::uniform_real_distribution<double> unit(-1, 1), angle(0, 1.2);
  for (int trial = 0; trial < 300; ++trial)
  {
    std::vector<atp::NormalCone> cones(std::size_t(1 + trial % 5));
    const double spread = trial % 3 == 0 ? 1 : 0.2; // axes all over, or close together
    for (atp::NormalCone& c : cones)
    {
      c.Axis[0] = spread * unit(random);
      c.Axis[1] = spread * unit(random);
      c.Axis[2] = 1;
      const double length = std::sqrt(c.Axis[0] * c.Axis[0] + c.Axis[1] * c.Axis[1] + 1);
      for (double& x : c.Axis)
      {
        x /= length;
      }
      c.Cos = std::cos(angle(random));
      c.Empty = false;
    }
    cones.push_back(atp::NormalCone()); // empty: ignored
    const atp::NormalCone outer = atp::EnclosingCone(cones);
    float axis[3], cosine;
    atp::StoreCone(outer, axis, cosine);
    const double storedAxis[3] = { axis[0], axis[1], axis[2] };
    const atp::NormalCone stored = atp::LoadCone(axis, cosine);
    for (const atp::NormalCone& c : cones)
    {
      if (c.Empty)
      {
        continue;
      }
      ASSERT_LE(AngleBetween(outer.Axis, c.Axis) + HalfAngle(c), HalfAngle(outer) + 1e-12) << "trial " << trial;
      ASSERT_LE(AngleBetween(storedAxis, c.Axis) + HalfAngle(c), HalfAngle(stored) + 1e-12) << "trial " << trial;
    }
  }
  atp::NormalCone everyWay;
  everyWay.Cos = -1;
  everyWay.Empty = false;
  EXPECT_EQ(atp::EnclosingCone({ everyWay }).Cos, -1);
}
