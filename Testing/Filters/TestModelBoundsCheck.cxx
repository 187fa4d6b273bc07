// What `atp verify` checks of a model's bounds: a built model passes, and every kind of bound
// that misses its patch or breaks the saturation is reported.
#include "ModelRewrite.h"
#include "TestModel.h"
#include "atpCutIndex.h"
#include "atpModelBoundsCheck.h"
#include "atpModelFile.h"
#include "atpPatchCodec.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

namespace
{

/// Problems of all of a model's patches.
std::vector<std::string> AllPatchProblems(const atp::ModelFile& model)
{
  std::vector<std::string> problems;
  atp::PatchMesh patch;
  for (std::size_t i = 0; i < model.NodeCount(); ++i)
  {
    model.DecodePatch(i, patch);
    for (const std::string& p : atp::PatchProblems(model.Header(), i, model.Node(i), patch))
    {
      problems.push_back(p);
    }
  }
  return problems;
}

void ExpectProblem(const std::vector<std::string>& problems, const std::string& fragment)
{
  bool found = false;
  for (const std::string& p : problems)
  {
    found = found || p.find(fragment) != std::string::npos;
  }
  EXPECT_TRUE(found) << "no problem says \"" << fragment << "\" among " << problems.size();
}

void ExpectOneProblem(const std::vector<std::string>& problems, const std::string& fragment)
{
  ASSERT_EQ(problems.size(), 1u) << (problems.empty() ? "none" : problems[0]);
  EXPECT_NE(problems[0].find(fragment), std::string::npos) << problems[0];
}

TEST(ModelBoundsCheck, ABuiltModelPasses)
{
  const atp::ModelFile model = atp::ModelFile::Open(atp::test::TorusModel());
  EXPECT_EQ(atp::SaturationProblems(model, atp::CutIndex(model)), std::vector<std::string>());
  EXPECT_EQ(AllPatchProblems(model), std::vector<std::string>());
}

TEST(ModelBoundsCheck, BoundsThatMissTheirPatchAreReported)
{
  const atp::ModelFile model = atp::ModelFile::Open(atp::test::TorusModel());
  // A node with a narrow cone and a few hundred triangles.
  std::size_t i = 0;
  while (i < model.NodeCount() && (model.Node(i).ConeCos < 0.5f || model.Node(i).TriangleCount < 100))
  {
    ++i;
  }
  ASSERT_LT(i, model.NodeCount());
  atp::PatchMesh patch;
  model.DecodePatch(i, patch);
  const atp::ModelNode good = model.Node(i);
  ASSERT_TRUE(atp::PatchProblems(model.Header(), i, good, patch).empty());
  const std::string node = "node " + std::to_string(i) + ": ";

  atp::ModelNode bad = good;
  bad.TriangleCount -= 1;
  ExpectOneProblem(atp::PatchProblems(model.Header(), i, bad, patch),
    node + "the patch holds " + std::to_string(good.TriangleCount) + " triangles, the node says");

  bad = good;
  bad.VertexCount -= 1;
  ExpectOneProblem(atp::PatchProblems(model.Header(), i, bad, patch), node + "the patch holds ");

  bad = good;
  bad.Sphere[3] *= 0.9f;
  ExpectOneProblem(atp::PatchProblems(model.Header(), i, bad, patch), node + "vertex ");

  bad = good;
  bad.Sphere[0] += 0.2f * good.Sphere[3];
  bad.SaturatedSphere[3] *= 2; // only the tight sphere is off
  ExpectOneProblem(atp::PatchProblems(model.Header(), i, bad, patch), node + "vertex ");

  bad = good;
  bad.ConeCos = 0.5f * (1 + good.ConeCos); // narrower
  ExpectOneProblem(atp::PatchProblems(model.Header(), i, bad, patch), "lies outside the normal cone");

  bad = good;
  for (float& a : bad.ConeAxis)
  {
    a = -a;
  }
  ExpectOneProblem(atp::PatchProblems(model.Header(), i, bad, patch), "lies outside the normal cone");

  bad = good;
  for (float& a : bad.ConeAxis)
  {
    a *= 2; // the same directions, but the cut reads the axis as a unit vector
  }
  ExpectOneProblem(atp::PatchProblems(model.Header(), i, bad, patch), "its normal cone's axis has length 1.99");

  bad = good;
  bad.ConeAxis[0] = bad.ConeAxis[1] = bad.ConeAxis[2] = 0;
  ExpectProblem(atp::PatchProblems(model.Header(), i, bad, patch), "its normal cone's axis has length 0, not 1");

  bad = good;
  bad.ConeCos = -1; // every direction: any axis will do
  bad.ConeAxis[0] = bad.ConeAxis[1] = bad.ConeAxis[2] = 0;
  EXPECT_TRUE(atp::PatchProblems(model.Header(), i, bad, patch).empty());

  atp::ModelHeader colored = model.Header();
  colored.Flags |= atp::ModelFlagColors;
  ExpectOneProblem(atp::PatchProblems(colored, i, good, patch), node + "the patch has no colors, the model says patches have");

  bad = good;
  bad.SaturatedSphere[3] = 0.5f * good.Sphere[3];
  ExpectOneProblem(atp::PatchProblems(model.Header(), i, bad, patch), "its sphere pokes out of its saturated sphere");
}

TEST(ModelBoundsCheck, SaturationThatDiffersOrDoesNotNestIsReported)
{
  const std::string path = atp::test::TempPath("bounds-check.atp");
  const std::vector<std::uint8_t> good = atp::test::ReadAll(atp::test::TorusModel());
  const auto problems = [&](const atp::test::Edit& edit) {
    atp::test::WriteAll(path, good);
    atp::test::Rewrite(path, edit, atp::test::Seal::All);
    const atp::ModelFile model = atp::ModelFile::Open(path);
    return atp::SaturationProblems(model, atp::CutIndex(model));
  };
  const atp::ModelFile model = atp::ModelFile::Open(atp::test::TorusModel());
  const atp::CutIndex diamonds(model);
  // A diamond of two or more members below the roots', with children, whose second member's
  // parent has a larger saturated error: there is room to raise the member's.
  const auto suits = [&](std::uint32_t d) {
    if (diamonds.MembersEnd(d) - diamonds.MembersBegin(d) < 2)
    {
      return false;
    }
    const atp::ModelNode& second = model.Node(diamonds.MembersBegin(d)[1]);
    return second.Children[0] >= 0 && second.Parent >= 0 &&
      model.Node(std::size_t(second.Parent)).SaturatedError > second.SaturatedError;
  };
  std::uint32_t d = 1;
  while (d < diamonds.DiamondCount() && !suits(d))
  {
    ++d;
  }
  ASSERT_LT(d, diamonds.DiamondCount());
  const std::uint32_t first = diamonds.MembersBegin(d)[0], second = diamonds.MembersBegin(d)[1];
  const std::string differs = "node " + std::to_string(second) +
    ": its saturated error or sphere differs from that of node " + std::to_string(first);

  ExpectProblem(problems([&](atp::ModelHeader&, std::vector<atp::ModelNode>& n, auto&) {
    n[second].SaturatedSphere[0] += 1e-3f * n[second].SaturatedSphere[3];
  }), differs);

  ExpectOneProblem(problems([&](atp::ModelHeader&, std::vector<atp::ModelNode>& n, auto&) {
    // Still monotone down the tree: only the diamond's equality breaks.
    atp::ModelNode& member = n[second];
    member.SaturatedError = 0.5f * (member.SaturatedError + n[std::size_t(member.Parent)].SaturatedError);
  }), differs);

  // The whole diamond's saturated spheres shrunk alike: its members' children poke out.
  const std::vector<std::string> found = problems([&](atp::ModelHeader&, std::vector<atp::ModelNode>& n, auto&) {
    for (const std::uint32_t* m = diamonds.MembersBegin(d); m != diamonds.MembersEnd(d); ++m)
    {
      n[*m].SaturatedSphere[3] *= 0.25f;
    }
  });
  ASSERT_FALSE(found.empty());
  for (const std::string& p : found)
  {
    EXPECT_NE(p.find("its saturated sphere pokes out of its parent's"), std::string::npos) << p;
  }
  std::remove(path.c_str());
}

} // namespace
