// The command line's shared helpers (cli/common.cpp) where a run cannot reach them cheaply:
// the solvers report a map that is not finite as numerical-error, and inputs that would make
// one are refused, so write_map's refusal is tested here.
#include <gtest/gtest.h>

#include <filesystem>
#include <limits>
#include <string>

#include "common.h"
#include "strictmin/io/input_error.h"
#include "strictmin/mesh/generators.h"

using namespace strictmin;
namespace fs = std::filesystem;

namespace {

fs::path fresh_folder() {
  const fs::path dir = fs::temp_directory_path() /
                       ("strictmin-cli-common-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

}  // namespace

TEST(WriteMap, AMapThatIsNotFiniteIsNotWrittenAndTheRunGoesOn) {
  const fs::path dir = fresh_folder();
  Mesh map = make_grid(2, 2);
  map.V(3, 1) = std::numeric_limits<double>::quiet_NaN();
  const std::string path = (dir / "map.obj").string();
  ::testing::internal::CaptureStderr();
  const std::string written = cli::write_map(path, map, SolveStatus::NumericalError);
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(written, "");  // the summary's output: none
  EXPECT_FALSE(fs::exists(path));
  EXPECT_NE(err.find("map not written to " + path + ": its coordinates are not finite (status numerical-error)"),
            std::string::npos)
      << err;
  EXPECT_TRUE(fs::is_empty(dir));  // no temporary left either
  fs::remove_all(dir);
}

TEST(WriteMap, UvsThatAreNotFiniteAreNotWrittenEither) {
  const fs::path dir = fresh_folder();
  Mesh map = make_grid(2, 2);
  map.UV = map.V;
  map.FUV = map.F;
  map.UV(0, 0) = std::numeric_limits<double>::infinity();
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(cli::write_map((dir / "uv.obj").string(), map, SolveStatus::NumericalError), "");
  EXPECT_NE(::testing::internal::GetCapturedStderr().find("not finite"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "uv.obj"));
  fs::remove_all(dir);
}

TEST(WriteMap, AFiniteMapIsWrittenAndNoPathWritesNothing) {
  const fs::path dir = fresh_folder();
  const Mesh map = make_grid(2, 2);
  const std::string path = (dir / "map.obj").string();
  EXPECT_EQ(cli::write_map(path, map, SolveStatus::Solved), path);
  EXPECT_TRUE(fs::exists(path));
  EXPECT_EQ(cli::write_map("", map, SolveStatus::Solved), "");
  // Other refusals stay errors (an unknown format).
  EXPECT_THROW(cli::write_map((dir / "map.stl").string(), map, SolveStatus::Solved), InputError);
  fs::remove_all(dir);
}
