#include <cstdlib>

#include "hexdom/quality/report.h"
#include "test_common.h"

using namespace hexdom;

TEST(ToJson, EmptyTypesAreNullAndKeysArePresent) {
  quality::QualityReport r = quality::quality_report(mesh::Mesh{Eigen::MatrixXd(0, 3), mesh::CellMatrix(0, 8),
                                                                Eigen::VectorXi(0), Eigen::VectorXi(0), {}});
  const std::string j = quality::to_json(r);
  for (const char* key : {"\"hex\": {\"count\": 0, \"sj_min\": null, \"sj_mean\": null, \"inverted\": 0, "
                          "\"edge_ratio_min\": null, \"edge_ratio_max\": null",
                          "\"prism\": {", "\"tet\": {", "\"total_volume\": 0"})
    EXPECT_NE(j.find(key), std::string::npos) << key << " in " << j;
}

TEST(ToJson, NumbersRoundTripExactly) {
  quality::QualityReport r;
  r.hex.count = 2;
  r.hex.sj_min = -0.4509443843940587;
  r.hex.sj_mean = 1.0 / 3.0;
  r.hex.edge_ratio_min = 1.0;
  r.hex.edge_ratio_max = 1e30;
  const std::string j = quality::to_json(r);
  auto value = [&](const std::string& key) {
    const size_t at = j.find("\"" + key + "\": ");
    EXPECT_NE(at, std::string::npos) << key;
    return std::strtod(j.c_str() + at + key.size() + 4, nullptr);
  };
  EXPECT_EQ(value("sj_min"), r.hex.sj_min);
  EXPECT_EQ(value("sj_mean"), r.hex.sj_mean);
  EXPECT_EQ(value("edge_ratio_max"), 1e30);
}
