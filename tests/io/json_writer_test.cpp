// The one model-file writer (src/io/json_writer.hpp): its layout and its numbers, and that
// every model type goes through it (the files of examples/ written back read the same).
#include "io/json_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "pdesurf/spectral_io.hpp"
#include "support/examples.hpp"

namespace pdesurf {
namespace {

using detail::ModelJson;
using detail::writeModelJson;

/// The lines of `text`.
std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(JsonWriter, PointsTakeALineEachObjectsALineWhenTheyFit) {
  ModelJson doc{{"type", "x"}, {"point", {0.5, -1, 2}}, {"points", ModelJson::array()}};
  for (int i = 0; i < 40; ++i) doc["points"].push_back({i, i + 0.25, -i});
  doc["frames"].push_back({{"vertices", {0, 1, 2, 3, 4, 5, 6, 7}}, {"a1", {1, 2.5, 3}}});
  ModelJson wide;  // wider than a line: one member per line
  for (const char* key : {"aaaaaaaaaaaa", "bbbbbbbbbbbb", "cccccccccccc", "dddddddddddd"})
    wide[key] = {1.0 / 3.0, 2.0 / 3.0};
  doc["frames"].push_back(wide);
  const std::vector<std::string> lines = linesOf(writeModelJson(doc));
  ASSERT_EQ(lines.size(), 1u + 2u + 42u + 1u + 1u + 6u + 1u + 1u);
  EXPECT_EQ(lines[0], "{");
  EXPECT_EQ(lines[1], "  \"type\": \"x\",");
  EXPECT_EQ(lines[2], "  \"point\": [0.5, -1, 2],");
  EXPECT_EQ(lines[3], "  \"points\": [");
  EXPECT_EQ(lines[4], "    [0, 0.25, 0],");
  EXPECT_EQ(lines[43], "    [39, 39.25, -39]");
  EXPECT_EQ(lines[44], "  ],");
  EXPECT_EQ(lines[45], "  \"frames\": [");
  EXPECT_EQ(lines[46], "    {\"vertices\": [0, 1, 2, 3, 4, 5, 6, 7], \"a1\": [1, 2.5, 3]},");
  EXPECT_EQ(lines[47], "    {");
  EXPECT_EQ(lines[48], "      \"aaaaaaaaaaaa\": [0.3333333333333333, 0.6666666666666666],");
  EXPECT_EQ(lines[52], "    }");
  EXPECT_EQ(lines[53], "  ]");
  EXPECT_EQ(lines[54], "}");
  for (const std::string& line : lines) EXPECT_LE(line.size(), 100u) << line;
}

TEST(JsonWriter, NumbersReadBackToTheSameDoubles) {
  const std::vector<double> values = {
      0.1, 1.0 / 3.0, 1e-300, -123456.789e10, 0.9999999999999999, 5e-324, 1e308, -0.0, 2.0, 1e21};
  ModelJson doc{{"values", values}};
  const ModelJson back = ModelJson::parse(writeModelJson(doc));
  ASSERT_EQ(back["values"].size(), values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    EXPECT_EQ(back["values"][i].get<double>(), values[i]) << i;
    EXPECT_EQ(std::signbit(back["values"][i].get<double>()), std::signbit(values[i])) << i;
  }
}

TEST(JsonWriter, StringsAreEscaped) {
  ModelJson doc{{"name", "a \"quoted\"\nname\\"}};
  EXPECT_EQ(ModelJson::parse(writeModelJson(doc))["name"], "a \"quoted\"\nname\\");
}

// Every example through parseModel and the writer: the same model again, and the text a fixed
// point, whatever the type.
TEST(JsonWriter, EveryExampleWrittenBackReadsTheSame) {
  for (const std::string& file : testing::exampleFiles()) {
    const std::string text = serializeModel(loadModel(file));
    EXPECT_EQ(text.substr(0, 2), "{\n") << file;
    EXPECT_EQ(serializeModel(parseModel(text, file)), text) << file;
  }
}

}  // namespace
}  // namespace pdesurf
