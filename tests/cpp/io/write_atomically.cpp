#include <fstream>
#include <stdexcept>

#include "hexdom/io/text.h"
#include "io_test_util.h"

using namespace hexdom;

namespace {
std::string content(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}
}  // namespace

TEST(WriteAtomically, ThrowingBodyLeavesNoFile) {
  const std::string path = test::temp_path("atomic_new.txt");
  std::filesystem::remove(path);
  EXPECT_THROW(io::write_atomically(path, false, [](std::ostream& out) {
                 out << "half";
                 throw std::runtime_error("stop");
               }),
               std::runtime_error);
  EXPECT_EQ(test::files_starting_with(path), 0);
}

TEST(WriteAtomically, ThrowingBodyKeepsThePreviousFile) {
  const std::string path = test::temp_path("atomic_old.txt");
  test::write_text(path, "previous");
  EXPECT_THROW(io::write_atomically(path, false, [](std::ostream& out) {
                 out << "half";
                 throw InputError("x");
               }),
               InputError);
  EXPECT_EQ(content(path), "previous");
  EXPECT_EQ(test::files_starting_with(path), 1);
}

TEST(WriteAtomically, SuccessReplacesTheFile) {
  const std::string path = test::temp_path("atomic_replace.txt");
  test::write_text(path, "previous");
  io::write_atomically(path, false, [](std::ostream& out) { out << "new"; });
  EXPECT_EQ(content(path), "new");
  EXPECT_EQ(test::files_starting_with(path), 1);
}
