// trajectory.csv and summary.json `columns` (DESIGN section 4): every data field reads as a
// float the way pandas infers types (a column of "0" would become int64), and every column
// has a unit, a frame entry and a description, in CSV order.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "generated_scenes.hpp"
#include "run_stiction.hpp"

namespace fs = std::filesystem;

namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  std::string f;
  while (std::getline(in, f, ',')) fields.push_back(f);
  return fields;
}

// pandas' inference: a field made of an optional sign and digits only is an integer; a
// column of such fields becomes int64. A float field parses completely with strtod.
bool reads_as_float(const std::string& field) {
  if (field.empty()) return false;
  const std::size_t digits = field.find_first_not_of("+-0123456789");
  if (digits == std::string::npos) return false;  // integer literal
  char* end = nullptr;
  std::strtod(field.c_str(), &end);
  return end == field.c_str() + field.size();
}

void check_run(const fs::path& dir, const std::string& scene) {
  const auto outcome = stiction::testing::run_stiction(
      {"run", scene, "--no-video", "--no-plots", "--quiet", "--out", "out"}, dir);
  INFO(outcome.out);
  REQUIRE(outcome.code == 0);
  std::ifstream csv(dir / "out" / "trajectory.csv");
  std::string line;
  REQUIRE(std::getline(csv, line));
  const std::vector<std::string> header = split(line);
  int rows = 0, zero_fields = 0;
  while (std::getline(csv, line)) {
    const std::vector<std::string> fields = split(line);
    REQUIRE(fields.size() == header.size());
    for (std::size_t c = 0; c < fields.size(); ++c) {
      INFO("column " << header[c] << " row " << rows << ": '" << fields[c] << "'");
      REQUIRE(reads_as_float(fields[c]));
      if (std::strtod(fields[c].c_str(), nullptr) == 0.0) ++zero_fields;
    }
    ++rows;
  }
  CHECK(rows > 10);
  CHECK(zero_fields > 0);  // the case that used to be written as "0"

  std::ifstream in(dir / "out" / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(in);
  REQUIRE(summary.contains("columns"));
  const nlohmann::json& columns = summary["columns"];
  REQUIRE(columns.size() == header.size());
  for (std::size_t c = 0; c < header.size(); ++c) {
    INFO(header[c]);
    CHECK(columns[c]["name"] == header[c]);
    CHECK(!columns[c]["unit"].get<std::string>().empty());
    CHECK(columns[c].contains("frame"));
    CHECK(!columns[c]["description"].get<std::string>().empty());
  }
  CHECK(columns[0]["unit"] == "s");
}

}  // namespace

TEST_CASE("every CSV data column reads as float and is described in summary.json",
          "[app][columns]") {
  const fs::path dir = stiction::testing::scratch_dir("stiction_test_columns_", "csv");
  check_run(dir, "sphere_roll");  // the sphere's q.x, q.z, w.x, w.z ... stay exactly 0
  check_run(
      dir,
      stiction::testing::write_scene(dir, "arm", stiction::testing::arm_scene(3, 7, 0.3)).string());
  check_run(dir, stiction::testing::write_scene(dir, "floor",
                                                stiction::testing::slope_to_floor_scene(0.3))
                     .string());
}

TEST_CASE("the body-frame angular velocity says so in summary.json", "[app][columns]") {
  const fs::path dir = stiction::testing::scratch_dir("stiction_test_columns_", "frame");
  const auto outcome =
      stiction::testing::run_stiction({"run", "sphere_roll", "--duration", "0.05", "--no-video",
                                       "--no-plots", "--quiet", "--out", "out"},
                                      dir);
  REQUIRE(outcome.code == 0);
  std::ifstream in(dir / "out" / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(in);
  bool found = false;
  for (const auto& c : summary["columns"]) {
    if (c["name"] == "sphere.w.y") {
      found = true;
      CHECK(c["frame"] == "body");
      CHECK(c["unit"] == "rad/s");
    }
    if (c["name"] == "sphere.v.x") CHECK(c["unit"] == "m/s");
    if (c["name"] == "ground.f.z") CHECK(c["unit"] == "N");
  }
  CHECK(found);
}
