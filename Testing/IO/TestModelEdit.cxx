// SetModelErrorScale on a real model: it still opens, with the new scale, and no other byte of
// the file changed; a file that is no valid model, or a bad scale, is refused and left as it was.
#include "atpModelEdit.h"
#include "atpModelFile.h"
#include "atpModelFormat.h"
#include "vtkATPBuilder.h"

#include "vtkNew.h"
#include "vtkSphereSource.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <unistd.h>

namespace
{
using namespace atp;

std::string ReadAll(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void WriteAll(const std::string& path, const std::string& bytes)
{
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

/// A model of a tessellated sphere, several levels deep, removed when the test ends.
class ModelEdit : public ::testing::Test
{
protected:
  void SetUp() override
  {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetThetaResolution(64);
    sphere->SetPhiResolution(64);
    sphere->Update();
    vtkNew<vtkATPBuilder> builder;
    builder->SetInputData(sphere->GetOutput());
    builder->SetFileName(Path.c_str());
    builder->SetLeafCapacity(500);
    builder->SetPatchBudget(200);
    ASSERT_EQ(builder->Build(), 1) << builder->GetErrorMessage();
    ASSERT_GT(ModelFile::Open(Path).NodeCount(), 6u) << "no level below the roots";
  }
  void TearDown() override { std::remove(Path.c_str()); }

  const std::string Path =
    "/tmp/atp-test-model-edit-" + std::to_string(::getpid()) + ".atp";
};

TEST_F(ModelEdit, ChangesTheErrorScaleAndNothingElse)
{
  const std::string before = ReadAll(Path);
  ASSERT_GT(before.size(), sizeof(ModelHeader));
  ASSERT_NE(ModelFile::Open(Path).Header().ErrorScale, 2.5f);

  SetModelErrorScale(Path, 2.5f);

  const ModelFile model = ModelFile::Open(Path);
  EXPECT_EQ(model.Header().ErrorScale, 2.5f);
  EXPECT_TRUE(model.Verify().empty());
  const std::string after = ReadAll(Path);
  ASSERT_EQ(after.size(), before.size());
  EXPECT_TRUE(after.compare(sizeof(ModelHeader), std::string::npos, before,
                sizeof(ModelHeader), std::string::npos) == 0)
    << "bytes after the header changed";
  for (std::size_t i = 0; i < sizeof(ModelHeader); ++i)
  {
    const bool scale = i >= offsetof(ModelHeader, ErrorScale) &&
      i < offsetof(ModelHeader, ErrorScale) + sizeof(float);
    const bool checksum = i >= offsetof(ModelHeader, HeaderChecksum);
    if (!scale && !checksum)
    {
      EXPECT_EQ(after[i], before[i]) << "header byte " << i << " changed";
    }
  }

  // Back to the original value: the original bytes, checksum included.
  SetModelErrorScale(Path, reinterpret_cast<const ModelHeader*>(before.data())->ErrorScale);
  EXPECT_EQ(ReadAll(Path), before);
}

TEST_F(ModelEdit, RefusesAnInvalidScaleAndLeavesTheModel)
{
  const std::string before = ReadAll(Path);
  EXPECT_THROW(SetModelErrorScale(Path, -1.0f), ModelError);
  EXPECT_THROW(SetModelErrorScale(Path, std::nanf("")), ModelError);
  EXPECT_THROW(SetModelErrorScale(Path, HUGE_VALF), ModelError);
  EXPECT_EQ(ReadAll(Path), before);
  SetModelErrorScale(Path, 0.0f); // zero is valid: the coarsest cut everywhere
  EXPECT_EQ(ModelFile::Open(Path).Header().ErrorScale, 0.0f);
}

TEST_F(ModelEdit, RefusesAFileThatIsNoModelAndLeavesIt)
{
  const std::string text = Path + ".txt";
  WriteAll(text, std::string(1000, 'x'));
  try
  {
    SetModelErrorScale(text, 2.0f);
    ADD_FAILURE() << "a text file was accepted";
  }
  catch (const ModelError& e)
  {
    EXPECT_NE(std::string(e.what()).find("not an ATP model"), std::string::npos) << e.what();
  }
  EXPECT_EQ(ReadAll(text), std::string(1000, 'x'));
  std::remove(text.c_str());

  EXPECT_THROW(SetModelErrorScale(Path + ".missing", 2.0f), ModelError);
}

TEST_F(ModelEdit, RefusesACorruptModelAndLeavesIt)
{
  // A damaged node section: the header alone would pass, so this proves the whole model is
  // validated before anything is written.
  std::string bytes = ReadAll(Path);
  bytes[reinterpret_cast<const ModelHeader*>(bytes.data())->NodeSectionOffset + 35] ^= 0x10;
  WriteAll(Path, bytes);
  try
  {
    SetModelErrorScale(Path, 2.0f);
    ADD_FAILURE() << "a corrupt model was accepted";
  }
  catch (const ModelError& e)
  {
    EXPECT_NE(std::string(e.what()).find("node section checksum"), std::string::npos) << e.what();
  }
  EXPECT_EQ(ReadAll(Path), bytes);
}

} // namespace
