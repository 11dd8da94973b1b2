#include <charconv>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include <catch2/catch.hpp>
#include <limits>
#include <nlohmann/json.hpp>

#include "io/atomic_file.hpp"
#include "io/csv_writer.hpp"
#include "io/summary.hpp"

using namespace stiction;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("stiction_test_io_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

int entries(const fs::path& dir) {
  int n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}

}  // namespace

TEST_CASE("csv: header, t first, numbers read back exactly") {
  core::Trajectory tr({"t", "ball.p.x", "ball.p.z"});
  const double a[] = {0.0, 0.1, 1.0 / 3.0};
  const double b[] = {1e-3, -2.5e-17, 123456789.123456789};
  tr.append(a);
  tr.append(b);
  const std::string csv = io::to_csv(tr);
  std::istringstream lines(csv);
  std::string line;
  std::getline(lines, line);
  CHECK(line == "t,ball.p.x,ball.p.z");
  std::vector<double> values;
  while (std::getline(lines, line)) {
    std::stringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) {
      double v = 0.0;
      std::from_chars(cell.data(), cell.data() + cell.size(), v);
      values.push_back(v);
    }
  }
  REQUIRE(values.size() == 6);
  CHECK(values[2] == 1.0 / 3.0);  // bit-exact round trip
  CHECK(values[4] == -2.5e-17);
  CHECK(values[5] == 123456789.123456789);
  CHECK(csv.back() == '\n');
}

TEST_CASE("atomic file: nothing under the target name until commit, no temporary after") {
  const fs::path dir = fresh_dir("atomic");
  const fs::path target = dir / "data.csv";
  {
    io::AtomicFile f(target);
    f.write("half");
    CHECK_FALSE(fs::exists(target));
    CHECK(fs::exists(f.temporary()));
    CHECK(f.temporary().parent_path() == dir);  // same directory: rename is atomic
    f.write(" and the rest\n");
    f.commit();
  }
  CHECK(slurp(target) == "half and the rest\n");
  CHECK(entries(dir) == 1);
}

TEST_CASE("atomic file: an abandoned write leaves the previous file and no litter") {
  const fs::path dir = fresh_dir("abandon");
  const fs::path target = dir / "summary.json";
  io::write_file_atomically(target, "old\n");
  try {
    io::AtomicFile f(target);
    f.write("new but incomplete");
    throw std::runtime_error("simulated failure");
  } catch (const std::runtime_error&) {
  }
  CHECK(slurp(target) == "old\n");
  CHECK(entries(dir) == 1);
}

TEST_CASE("atomic file: an unwritable directory is an IoError") {
  CHECK_THROWS_AS(io::write_file_atomically("/nonexistent_dir_for_stiction/x.csv", "x"), io::IoError);
}

TEST_CASE("summary: fields, final row by column name, events, instability") {
  core::RunResult result;
  result.trajectory = core::Trajectory({"t", "b.v.x"});
  const double r0[] = {0.0, 2.0}, r1[] = {0.5, 1.5};
  result.trajectory.append(r0);
  result.trajectory.append(r1);
  result.steps = 5000;
  result.wall_seconds = 0.25;
  core::SlipMonitor monitor(1e-3);
  for (int k = 0; k <= 100; ++k) {
    const double t = k * 0.01;
    monitor.observe(t, core::Vec3(std::max(0.0, 0.5 - t), 0.0, 0.0));
  }
  result.slip_events.push_back({"ground", monitor});
  io::RunDescription run{"demo", "rk4", 1e-4, 0.5, 1000.0, 15, std::nullopt, std::nullopt};
  nlohmann::json s = nlohmann::json::parse(io::make_summary(run, result).dump());
  CHECK(s["scene"] == "demo");
  CHECK(s["integrator"] == "rk4");
  CHECK(s["dt"] == 1e-4);
  CHECK(s["duration"] == 0.5);
  CHECK(s["steps"] == 5000);
  CHECK(s["state_dim"] == 15);
  CHECK(s["wall_seconds"] == 0.25);
  CHECK(s["status"] == "ok");
  CHECK(s["final"]["t"] == 0.5);
  CHECK(s["final"]["b.v.x"] == 1.5);
  CHECK(s["events"]["ground"]["threshold"] == 1e-3);
  REQUIRE(s["events"]["ground"]["stick_time"].is_number());
  CHECK(s["events"]["ground"]["stick_time"].get<double>() == Approx(0.5).margin(0.011));
  CHECK(s["events"]["ground"]["events"][0]["kind"] == "stick");
  CHECK_FALSE(s.contains("instability"));

  result.instability = core::Instability{0.3, "ground", "state is not finite"};
  run.suggested_dt = 2.5e-5;
  s = nlohmann::json::parse(io::make_summary(run, result).dump());
  CHECK(s["status"] == "unstable");
  CHECK(s["instability"]["time"] == 0.3);
  CHECK(s["instability"]["component"] == "ground");
  CHECK(s["instability"]["suggested_dt"] == 2.5e-5);
}

TEST_CASE("csv: whole numbers are written as floats, other numbers unchanged") {
  auto text = [](double v) {
    std::string out;
    io::append_number(out, v);
    return out;
  };
  CHECK(text(0.0) == "0.0");
  CHECK(text(-0.0) == "-0.0");
  CHECK(text(12.0) == "12.0");
  CHECK(text(-3.0) == "-3.0");
  CHECK(text(0.1) == "0.1");
  CHECK(text(1e20) == "1e+20");
  CHECK(text(1.5e-7) == "1.5e-07");
  CHECK(text(std::numeric_limits<double>::quiet_NaN()) == "nan");
  CHECK(text(std::numeric_limits<double>::infinity()) == "inf");
  CHECK(std::stod(text(123456789.0)) == 123456789.0);
}
