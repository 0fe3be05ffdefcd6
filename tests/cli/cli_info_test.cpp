// `pdesurf info`'s one formatter for every method (apps/cli/info_command.hpp): a ModelInfo
// made here, written as a listing and as JSON.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "info_command.hpp"

namespace pdesurf::cli {
namespace {

/// An info with a plain fact, a worded one, a listing-only and a JSON-only one, and a box.
ModelInfo sampleInfo() {
  ModelInfo info;
  info.source = "m.json";
  info.name = "cup";
  info.facts = {{"type", "type", "toy", ""},
                {"strips", "strips", 3, "3 (1 pinned to 0)"},
                {"warning", "", 1, "cracks"},
                {"", "pinned_strips", 1, ""},
                boxFact(Vec3(0, -0.5, 0), Vec3(1, 2.25, 0.1))};
  return info;
}

TEST(CliInfoFormat, ListingPadsTheLabelsAndWordsEachFact) {
  EXPECT_EQ(infoListing(sampleInfo()),
            "model      m.json (cup)\n"
            "type       toy\n"
            "strips     3 (1 pinned to 0)\n"
            "warning    cracks\n"
            "bbox       [0, -0.5, 0] to [1, 2.25, 0.1]\n");
  ModelInfo unnamed = sampleInfo();
  unnamed.name.clear();
  EXPECT_EQ(infoListing(unnamed).substr(0, 18), "model      m.json\n");
}

TEST(CliInfoFormat, JsonListsTheKeyedFactsInOrderOrByKey) {
  ModelInfo info = sampleInfo();
  EXPECT_EQ(infoJson(info), R"({
  "model": "m.json",
  "name": "cup",
  "type": "toy",
  "strips": 3,
  "pinned_strips": 1,
  "bbox": {
    "min": [
      0.0,
      -0.5,
      0.0
    ],
    "max": [
      1.0,
      2.25,
      0.1
    ]
  }
}
)");
  // In key order, records inside included; the same values.
  info.keysSorted = true;
  const std::string sorted = infoJson(info);
  EXPECT_LT(sorted.find("\"bbox\""), sorted.find("\"model\""));
  EXPECT_LT(sorted.find("\"max\""), sorted.find("\"min\""));
  EXPECT_LT(sorted.find("\"pinned_strips\""), sorted.find("\"strips\""));
  EXPECT_EQ(nlohmann::json::parse(sorted), nlohmann::json::parse(infoJson(sampleInfo())));
}

TEST(CliInfoFormat, ValuesAreWrittenAsTheyAre) {
  using Json = nlohmann::ordered_json;
  EXPECT_EQ(infoValueText(Json(0.1)), "0.1");
  EXPECT_EQ(infoValueText(Json(1e-15)), "1e-15");
  EXPECT_EQ(infoValueText(Json(-3)), "-3");
  EXPECT_EQ(infoValueText(Json(false)), "no");
  EXPECT_EQ(infoValueText(Json::array({1, 2.5})), "[1, 2.5]");
  EXPECT_EQ(infoValueText(Json{{"u", "clamped"}}), R"({"u":"clamped"})");
}

}  // namespace
}  // namespace pdesurf::cli
