// The paper's values file (`duskmap report --paper`): a key the report does
// not know is refused, naming the file and the key, instead of leaving its
// values out of the tables without a word (issue 48).
#include "slam/report/paper_reference.h"

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "slam/core/check.h"
#include "tests/testing/error_of.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {

const std::string kPaperFile = std::string(DUSKMAP_SOURCE_DIR) + "/configs/paper_results.json";

nlohmann::json PaperJson() { return nlohmann::json::parse(std::ifstream(kPaperFile)); }

std::string Write(const std::string& name, const nlohmann::json& json) {
  const std::string path = testing::ProcessTempPath("paper_" + name);
  std::ofstream(path) << json.dump(1);
  return path;
}

std::string LoadError(const std::string& path) {
  return testing::ErrorOf([&] { PaperReference::Load(path); });
}

TEST(PaperReference, TheProjectsAndTheSharedPaperFilesAreRead) {
  EXPECT_EQ(LoadError(kPaperFile), "");
  const std::string shared = std::string(DUSKMAP_SHARED_DIR) + "/reference/paper_results.json";
  if (!std::filesystem::exists(shared)) GTEST_SKIP() << shared << " not found (../shared is absent)";
  EXPECT_EQ(LoadError(shared), "");
}

TEST(PaperReference, UnknownKeysAreRefusedNamingFileAndKey) {
  nlohmann::json misspelt = PaperJson();
  misspelt["table_ate"] = misspelt["table_ate_mm"];
  misspelt.erase("table_ate_mm");
  const std::string top = Write("top.json", misspelt);
  EXPECT_EQ(LoadError(top).rfind(top + ": unknown key 'table_ate' (the report reads", 0), 0u) << LoadError(top);
  nlohmann::json metric = PaperJson();
  metric["table_cumulative_relocalization"]["relocalisation_pct"] = nlohmann::json::object();
  const std::string inner = Write("metric.json", metric);
  EXPECT_EQ(LoadError(inner), inner + ": unknown key 'table_cumulative_relocalization.relocalisation_pct'");
  // Notes and comments are free text.
  nlohmann::json noted = PaperJson();
  noted["table_timing"]["feature_detection_ms_note"] = "on a laptop";
  noted["_comment"] = "mine";
  EXPECT_EQ(LoadError(Write("noted.json", noted)), "");
  nlohmann::json no_columns = PaperJson();
  no_columns["table_ate_mm"].erase("columns");
  const std::string columns = Write("columns.json", no_columns);
  EXPECT_EQ(LoadError(columns), columns + ": table_ate_mm.columns: expected a list of feature codes");
  const std::string findings = Write("findings.json", {{"qualitative_findings", {1, 2}}});
  EXPECT_EQ(LoadError(findings), findings + ": qualitative_findings: expected a list of texts");
  const std::string list = Write("list.json", nlohmann::json::array());
  EXPECT_EQ(LoadError(list), list + ": expected a JSON object (the paper's values)");
}

TEST(PaperReference, FifoIsRefusedWithoutOpening) {
  alarm(120);  // ends the process should the reader block again
  const std::string fifo = testing::ProcessTempPath("paper_fifo.json");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(LoadError(fifo), fifo + ": is a FIFO (named pipe), not a regular file");
  alarm(0);
}

}  // namespace
}  // namespace duskmap
