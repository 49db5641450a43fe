// Inputs the fuzzers found (tests/fuzz/regressions/<reader>/, named by what they exercise): each must
// be answered by a mesh or an InputError naming the file, never a crash (the sanitizer builds
// catch an out-of-bounds access the plain build would let pass).
#include <filesystem>

#include "hexdom/io/mesh_io.h"
#include "io_test_util.h"

using namespace hexdom;

TEST(FuzzRegressions, EveryFoundInputIsAnsweredByAMeshOrAnInputError) {
  namespace fs = std::filesystem;
  const fs::path root = fs::path(HEXDOM_SOURCE_DIR) / "tests" / "fuzz" / "regressions";
  int files = 0;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    if (!e.is_regular_file()) continue;
    ++files;
    const std::string path = e.path().string();
    try {
      mesh::validate(io::read_mesh(path));
    } catch (const InputError& err) {
      EXPECT_EQ(err.path(), path) << err.what();
    }
  }
  EXPECT_GE(files, 1);
}
