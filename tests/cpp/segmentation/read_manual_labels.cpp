#include "hexdom/segmentation/read_manual_labels.h"

#include "hexdom/common/error.h"
#include "seg_test_util.h"

using namespace hexdom;

TEST(ReadManualLabels, ReadsTheRodOverrides) {
  const std::string path = test::data_path("hexdom/rod_demo/rod_manual.txt");
  HEXDOM_REQUIRE_DATA(path);
  auto m = segmentation::read_manual_labels(path);
  ASSERT_EQ(m.size(), 56u);
  EXPECT_EQ(m[0], std::make_pair(354, 1));  // "354 0": +X
  int minus_z = 0;
  for (const auto& [t, l] : m) minus_z += l == 6;
  EXPECT_EQ(minus_z, 17);  // the seventeen "... 5" lines
}

TEST(ReadManualLabels, SkipsBlankAndCommentLines) {
  const std::string path = test::temp_path("manual_ok.txt");
  test::write_text(path, "# overrides\n\n12 3\r\n$ ls-dyna style comment\n  7\t5  \n");
  auto m = segmentation::read_manual_labels(path);
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0], std::make_pair(12, 4));
  EXPECT_EQ(m[1], std::make_pair(7, 6));
}

TEST(ReadManualLabels, BadLinesNameFileAndLine) {
  const std::string path = test::temp_path("manual_bad.txt");
  for (const std::string& bad : {std::string("1 2\n3\n"), std::string("1 2\n4 6\n"), std::string("1 2\n-1 0\n"),
                                 std::string("1 2\nx y\n")}) {
    test::write_text(path, bad);
    try {
      segmentation::read_manual_labels(path);
      FAIL() << "no error for " << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("manual_bad.txt:2:"), std::string::npos) << e.what();
      EXPECT_EQ(e.line(), 2);
    }
  }
  EXPECT_THROW(segmentation::read_manual_labels(test::temp_path("no_such_manual.txt")), InputError);
}
