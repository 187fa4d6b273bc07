// The view-dependent cut: culling primitives, the diamond index, and the residency-aware cut
// that the renderer relies on (conforming while patches load, converging to the full cut).
#include "FaceNormal.h"
#include "MeshEdges.h"
#include "TestModel.h"

#include "atpCameraView.h"
#include "atpCut.h"
#include "atpCutIndex.h"
#include "atpModelFile.h"
#include "atpPatchCodec.h"
#include "atpTetra.h"

#include "vtkCamera.h"
#include "vtkNew.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <set>
#include <unistd.h>

namespace
{
using namespace atp::test;

atp::CullingCone Cone(double x, double y, double z, double halfAngleDegrees)
{
  const double length = std::sqrt(x * x + y * y + z * z);
  atp::CullingCone c;
  c.Axis[0] = float(x / length);
  c.Axis[1] = float(y / length);
  c.Axis[2] = float(z / length);
  c.Cos = float(std::cos(halfAngleDegrees * M_PI / 180));
  return c;
}

bool Holds(const atp::CullingCone& outer, const atp::CullingCone& inner)
{
  if (inner.IsEmpty() || outer.Cos <= -1)
  {
    return true;
  }
  const double dot = outer.Axis[0] * inner.Axis[0] + outer.Axis[1] * inner.Axis[1] + outer.Axis[2] * inner.Axis[2];
  // Float axes: a unit vector's dot with itself may read 1 - 6e-8, an angle of 3.5e-4.
  return std::acos(std::min(1.0, dot)) + std::acos(double(inner.Cos)) <= std::acos(double(outer.Cos)) + 5e-4;
}

TEST(Cut, MergedConesHoldBothCones)
{
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(-1, 1), angle(0, 100);
  for (int i = 0; i < 1000; ++i)
  {
    const atp::CullingCone a = Cone(unit(random), unit(random), unit(random), angle(random));
    const atp::CullingCone b = Cone(unit(random), unit(random), unit(random), angle(random));
    const atp::CullingCone m = atp::MergeCones(a, b);
    EXPECT_TRUE(Holds(m, a) && Holds(m, b));
    // Never wider than needed: at most the sum of both plus the angle between them.
    EXPECT_GE(std::acos(double(m.Cos)), std::max(std::acos(double(a.Cos)), std::acos(double(b.Cos))) - 1e-4);
  }
  const atp::CullingCone empty;
  EXPECT_EQ(atp::MergeCones(empty, Cone(1, 0, 0, 10)).Cos, Cone(1, 0, 0, 10).Cos);
}

TEST(Cut, BackfaceTestUsesConeAndSphere)
{
  atp::ViewPoint view; // eye at the origin
  const float ahead[4] = { 0, 0, -10, 1 };
  // Normals pointing away from the eye (along -z, the viewing direction): back faces.
  EXPECT_TRUE(atp::FacesAway(Cone(0, 0, -1, 20), ahead, view));
  // Facing the eye: front faces.
  EXPECT_FALSE(atp::FacesAway(Cone(0, 0, 1, 20), ahead, view));
  // A cone wide enough to hold a normal facing the eye, or a sphere around the eye: visible.
  EXPECT_FALSE(atp::FacesAway(Cone(0, 0, -1, 85), ahead, view));
  const float around[4] = { 0, 0, 0, 2 };
  EXPECT_FALSE(atp::FacesAway(Cone(0, 0, -1, 5), around, view));
  // The sphere's apparent size counts: a big sphere close by shows its rim.
  const float big[4] = { 0, 0, -2, 1.9f };
  EXPECT_FALSE(atp::FacesAway(Cone(0, 0, -1, 20), big, view));
}

TEST(Cut, FrustumTestUsesPlanes)
{
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0, 0, 10);
  camera->SetFocalPoint(0, 0, 0);
  const atp::ViewPoint view = atp::ViewFromCamera(camera, 400, 300, nullptr, 1, false);
  const float center[4] = { 0, 0, 0, 0.1f }, far[4] = { 50, 0, 0, 1 }, edge[4] = { 2.8f, 0, 0, 0.5f };
  EXPECT_FALSE(atp::OutsideFrustum(center, view));
  EXPECT_TRUE(atp::OutsideFrustum(far, view));
  EXPECT_FALSE(atp::OutsideFrustum(edge, view)); // straddles the side plane (tan 20 deg * 10 = 3.6 wide)
  EXPECT_NEAR(view.ViewAngleDegrees, 30, 1e-9);
}

TEST(Cut, IndexGroupsWholeDiamondsAndSaturatesCones)
{
  const atp::ModelFile model = atp::ModelFile::Open(TorusModel());
  const atp::CutIndex index(model);
  for (std::uint32_t n = 0; n < model.NodeCount(); ++n)
  {
    const std::uint32_t d = index.DiamondOf(n);
    EXPECT_NE(std::find(index.MembersBegin(d), index.MembersEnd(d), n), index.MembersEnd(d));
    const atp::ModelNode& node = model.Node(n);
    if (node.Children[0] >= 0)
    {
      // A split diamond is whole.
      EXPECT_EQ(std::size_t(index.MembersEnd(d) - index.MembersBegin(d)),
        atp::DiamondMembers(atp::TetId{ node.Tet }).size());
      for (const std::int32_t child : node.Children)
      {
        EXPECT_TRUE(Holds(index.SaturatedCone(n), index.SaturatedCone(std::uint32_t(child))));
      }
    }
    if (node.Parent >= 0)
    {
      const std::uint32_t parent = index.DiamondOf(std::uint32_t(node.Parent));
      EXPECT_NE(std::find(index.ParentsBegin(d), index.ParentsEnd(d), parent), index.ParentsEnd(d));
    }
  }
  EXPECT_EQ(index.ParentsBegin(0), index.ParentsEnd(0)); // the roots' diamond
}

/// A camera looking at the torus from a random direction and distance.
atp::ViewPoint RandomView(std::mt19937& random, bool culling)
{
  std::uniform_real_distribution<double> unit(-1, 1), distance(0.8, 25), tolerance(0.3, 8);
  vtkNew<vtkCamera> camera;
  double dir[3] = { unit(random), unit(random), unit(random) };
  const double length = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  const double d = distance(random);
  camera->SetPosition(dir[0] / length * d, dir[1] / length * d, dir[2] / length * d);
  camera->SetFocalPoint(unit(random), unit(random), unit(random));
  atp::ViewPoint view = atp::ViewFromCamera(camera, 640, 480, nullptr, tolerance(random), culling);
  if (!culling)
  {
    view.PlaneCount = 0;
  }
  return view;
}

TEST(Cut, WhileLoadingTheCutStaysCrackFreeAndConvergesToTheFullCut)
{
  const atp::ModelFile model = atp::ModelFile::Open(TorusModel());
  auto index = std::make_shared<const atp::CutIndex>(model);
  atp::CutSelector selector(model, index);
  const atp::PatchMesh finest = atp::ExtractCut(model, atp::SelectLevel(model, 64));
  const std::set<Position> boundary = EdgeEnds(OpenEdges(finest));
  std::mt19937 random(5);
  for (int v = 0; v < 24; ++v)
  {
    const bool culling = v % 2 == 1;
    const atp::ViewPoint view = RandomView(random, culling);
    std::set<std::uint32_t> loaded;
    const atp::ResidentFunction resident = [&](std::uint32_t n) {
      return model.Node(n).TriangleCount == 0 || loaded.count(n) > 0;
    };
    atp::CutResult cut;
    int rounds = 0;
    for (;; ++rounds)
    {
      selector.Select(view, 1, resident, cut);
      for (const std::uint32_t n : cut.Drawn)
      {
        ASSERT_TRUE(resident(n));
      }
      if (!culling && !cut.Drawn.empty())
      {
        // Without culling every partial cut is a whole surface: its only open edges are the
        // input's boundary.
        for (const Edge& e : OpenEdges(atp::ExtractCut(model, cut.Drawn)))
        {
          ASSERT_TRUE(boundary.count(e.first) && boundary.count(e.second))
            << "view " << v << " round " << rounds << ": a crack while loading";
        }
      }
      if (cut.Complete())
      {
        break;
      }
      // Load half of what is missing (at least one), as a slow disk would.
      for (std::size_t i = 0; i < std::max<std::size_t>(1, cut.Missing.size() / 2); ++i)
      {
        loaded.insert(cut.Missing[i]);
      }
      ASSERT_LT(rounds, 2000);
    }
    atp::CutResult full;
    selector.Select(view, 1, atp::ResidentFunction(), full);
    EXPECT_EQ(std::set<std::uint32_t>(cut.Drawn.begin(), cut.Drawn.end()),
      std::set<std::uint32_t>(full.Drawn.begin(), full.Drawn.end()))
      << "view " << v << ": converged to another cut";
  }
}

/// Whether nothing of the patch can be seen: each triangle lies outside one of the view's planes
/// or faces away from the eye.
bool Invisible(const atp::PatchMesh& patch, const atp::ViewPoint& view)
{
  for (std::size_t t = 0; t < patch.TriangleCount(); ++t)
  {
    double p[3][3];
    for (int k = 0; k < 3; ++k)
    {
      for (int a = 0; a < 3; ++a)
      {
        p[k][a] = patch.Positions[3 * std::size_t(patch.Indices[3 * t + std::size_t(k)]) + std::size_t(a)];
      }
    }
    bool outside = false;
    for (int i = 0; i < view.PlaneCount && !outside; ++i)
    {
      const double* plane = view.Planes[i];
      outside = true;
      for (const double* q : p)
      {
        outside = outside && plane[0] * q[0] + plane[1] * q[1] + plane[2] * q[2] + plane[3] < 0;
      }
    }
    if (outside)
    {
      continue;
    }
    const std::array<double, 3> n = FaceNormal(patch, t);
    // Every point of a flat triangle is seen from the same side.
    const double seen[3] = { view.Parallel ? view.Direction[0] : p[0][0] - view.Eye[0],
      view.Parallel ? view.Direction[1] : p[0][1] - view.Eye[1],
      view.Parallel ? view.Direction[2] : p[0][2] - view.Eye[2] };
    const bool away = view.BackfaceCulling && n[0] * seen[0] + n[1] * seen[1] + n[2] * seen[2] > 0;
    if (!away)
    {
      return false;
    }
  }
  return true;
}

TEST(Cut, CullingDropsOnlyInvisiblePatches)
{
  const atp::ModelFile model = atp::ModelFile::Open(TorusModel());
  const atp::QuantizationGrid grid = model.PatchGrid();
  std::mt19937 random(9);
  std::size_t culledSome = 0, dropped = 0, visibleKept = 0;
  atp::PatchMesh patch;
  for (int v = 0; v < 20; ++v)
  {
    atp::ViewPoint view = RandomView(random, true);
    const atp::ViewPoint culling = view;
    const std::vector<std::uint32_t> culled = atp::SelectCut(model, view);
    view.PlaneCount = 0;
    view.BackfaceCulling = false;
    const std::vector<std::uint32_t> all = atp::SelectCut(model, view);
    // Culling never changes which diamonds refine: the culled cut is a subset of the full one,
    // and what it leaves out cannot be seen.
    const std::set<std::uint32_t> culledSet(culled.begin(), culled.end());
    const std::set<std::uint32_t> allSet(all.begin(), all.end());
    for (const std::uint32_t n : culled)
    {
      EXPECT_TRUE(allSet.count(n));
    }
    for (const std::uint32_t n : all)
    {
      atp::DecodePatch(model.PatchData(n), model.Node(n).PatchBytes, grid, patch);
      if (!culledSet.count(n))
      {
        ++dropped;
        EXPECT_TRUE(Invisible(patch, culling)) << "view " << v << ": node " << n << " was visible";
      }
      else
      {
        visibleKept += !Invisible(patch, culling);
      }
    }
    culledSome += culled.size() < all.size();
  }
  std::printf("%zu patches culled, all invisible; %zu kept are visible\n", dropped, visibleKept);
  EXPECT_GT(culledSome, 5u);
  EXPECT_GT(visibleKept, dropped / 4) << "the invisibility test should tell kept patches apart";
}

} // namespace
