// `stiction sweep` as a user runs it: the sphere_roll grid against the closed form of a
// sphere released at rest on the ground with speed v0 (sliding ends at 2 v0 / (7 mu g), then
// it rolls at 5/7 v0), shards run as separate processes merged into the unsharded table,
// resume after an interruption, unstable points recorded, bad input; sweep.svg is valid SVG
// with one polyline per v0 in the order of the closed form.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "run_stiction.hpp"
#include "svg_check.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using stiction::testing::Outcome;

namespace {

// A command's arguments followed by more.
std::vector<std::string> joined(std::vector<std::string> args, const std::vector<std::string>& extra) {
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

fs::path scratch(const std::string& name) {
  return stiction::testing::scratch_dir("stiction_test_sweep_", name);
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream s(line);
  std::string cell;
  while (std::getline(s, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::size_t column(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i) {
      if (header[i] == name) return i;
    }
    FAIL("no column " << name);
    return 0;
  }
};

// The tables these tests write hold no quoted fields (no errors, no commas in values).
Table read_table(const fs::path& p) {
  std::stringstream in(read_text(p));
  Table t;
  std::string line;
  std::getline(in, line);
  t.header = split(line);
  while (std::getline(in, line)) t.rows.push_back(split(line));
  return t;
}

// The table's text without the wall-time column: the one field that differs between two
// runs of the same sweep.
std::string without_wall_time(const fs::path& p) {
  const Table t = read_table(p);
  const std::size_t wall = t.column("wall_s");
  std::string text;
  auto add = [&](const std::vector<std::string>& cells) {
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if (i == wall) continue;
      text += cells[i] + (i + 1 < cells.size() ? "," : "");
    }
    text += "\n";
  };
  add(t.header);
  for (const auto& r : t.rows) add(r);
  return text;
}

// A generated scene: a sphere of random size and mass with long names, resting on the
// ground in its static equilibrium (mass g / stiffness deep).
std::string resting_sphere(double radius, double mass) {
  const double k = 1e7, g = 9.8;
  std::ostringstream s;
  s.precision(17);
  s << "name = \"generated_resting_sphere\"\ngravity = [0.0, 0.0, " << -g << "]\n"
    << "[simulation]\ndt = 1e-4\nduration = 0.4\noutput_rate = 200.0\n"
    << "[bodies.a_sphere_with_a_rather_long_name_for_the_table]\ntype = \"rigid_body\"\n"
    << "mass = " << mass << "\nshape = \"sphere\"\nradius = " << radius << "\n"
    << "position = [0.0, 0.0, " << radius - mass * g / k << "]\nvelocity = [1.0, 0.0, 0.0]\n"
    << "[impedances.the_ground_contact_of_that_sphere]\ntype = \"kikuuwe_contact\"\n"
    << "body = \"a_sphere_with_a_rather_long_name_for_the_table\"\nnormal = [0.0, 0.0, 1.0]\n"
    << "stiffness = " << k << "\ndamping = 10.0\nmu = 0.3\n";
  return s.str();
}

}  // namespace

TEST_CASE("sweep: sphere_roll over mu and v0 matches 2 v0 / (7 mu g) at every point") {
  const fs::path dir = scratch("sphere");
  // Released at rest on the ground (static deflection m g / k below the radius).
  const Outcome o = stiction::testing::run_stiction(
      {"sweep", "sphere_roll", "--vary", "impedances.ground.mu=0.05:0.5:10", "--vary",
       "bodies.sphere.velocity[0]=1,2,4", "--set", "bodies.sphere.position=[0.0, 0.0, 0.199999706]",
       "--duration", "2.5", "--keep", "none", "--record", "sphere.v.x", "--out", "grid"},
      dir);
  INFO(o.out);
  REQUIRE(o.code == 0);
  const Table t = read_table(dir / "grid" / "sweep.csv");
  REQUIRE(t.rows.size() == 30);
  const std::size_t mu_c = t.column("impedances.ground.mu");
  const std::size_t v_c = t.column("bodies.sphere.velocity[0]");
  const std::size_t stick_c = t.column("ground.stick_time");
  const std::size_t vx_c = t.column("sphere.v.x");
  std::map<std::string, int> per_v0;
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    const auto& row = t.rows[r];
    CHECK(row[t.column("point")] == std::to_string(r));
    CHECK(row[t.column("status")] == "ok");
    const double mu = std::stod(row[mu_c]);
    const double v0 = std::stod(row[v_c]);
    ++per_v0[row[v_c]];
    const double expected = 2.0 * v0 / (7.0 * mu * 9.8);
    INFO("mu = " << mu << ", v0 = " << v0);
    REQUIRE_FALSE(row[stick_c].empty());
    // Released in contact and at rest vertically, the sphere slides with friction mu m g
    // from the first step: the stick times match the closed form to rounding.
    CHECK(std::stod(row[stick_c]) == Approx(expected).epsilon(1e-6));
    CHECK(std::stod(row[vx_c]) == Approx(5.0 / 7.0 * v0).epsilon(1e-6));
  }
  CHECK(per_v0 == std::map<std::string, int>{{"1", 10}, {"2", 10}, {"4", 10}});
  CHECK(std::stod(t.rows[1][mu_c]) == 0.05);  // the grid: the last key fastest
  CHECK(std::stod(t.rows[29][mu_c]) == 0.5);
  CHECK(fs::file_size(dir / "grid" / "sweep.png") > 1000);
  // The same figure as vectors: a well-formed SVG whose three series (v0 = 1, 2, 4, in that
  // order) are polylines of the ten mu values, falling with mu (y grows downwards), and
  // ordered as 2 v0 / (7 mu g) at every mu.
  const stiction::testing::SvgDocument svg =
      stiction::testing::parse_svg(read_text(dir / "grid" / "sweep.svg"));
  INFO(svg.error);
  REQUIRE(svg.well_formed);
  CHECK(svg.root == "svg");
  std::vector<std::vector<stiction::testing::SvgPoint>> series;
  for (const auto& path : svg.paths) {
    if (path.points.size() == 10 && path.style.find("fill:none") != std::string::npos)
      series.push_back(path.points);
  }
  REQUIRE(series.size() == 3);
  for (const auto& line : series) {
    for (std::size_t i = 1; i < line.size(); ++i) {
      CHECK(line[i].x > line[i - 1].x);
      CHECK(line[i].y > line[i - 1].y);
    }
  }
  for (std::size_t i = 0; i < 10; ++i) {
    CHECK(series[0][i].x == series[2][i].x);
    CHECK(series[0][i].y > series[1][i].y);
    CHECK(series[1][i].y > series[2][i].y);
  }
  CHECK_THAT(read_text(dir / "grid" / "sweep.md"), Contains("ok 30"));
  CHECK_FALSE(fs::exists(dir / "grid" / "points"));  // --keep none
}

TEST_CASE("sweep: four shards as separate processes merge into the unsharded table") {
  const fs::path dir = scratch("shards");
  std::ofstream(dir / "gen.toml") << resting_sphere(0.137, 0.71);
  const std::vector<std::string> sweep{
      "sweep",   "gen.toml",
      "--vary",  "impedances.the_ground_contact_of_that_sphere.mu=0.2:0.8:5:log",
      "--vary",  "bodies.a_sphere_with_a_rather_long_name_for_the_table.velocity[0]=0.3,0.6",
      "--quiet", "-j",
      "1"};
  auto with = [&](const std::vector<std::string>& extra) { return joined(sweep, extra); };
  REQUIRE(stiction::testing::run_stiction(with({"--out", "whole"}), dir).code == 0);

  // Four processes at once, as a job array would start them.
  // (Built with += only: GCC 12 warns, -Wrestrict, on some "literal" + string chains.)
  std::string command = "cd ";
  command += stiction::testing::shell_quote(dir.string());
  command += " && (";
  for (int k = 0; k < 4; ++k) {
    command += "SLURM_ARRAY_TASK_ID=";
    command += std::to_string(k + 1);
    command += " SLURM_ARRAY_TASK_MIN=1 SLURM_ARRAY_TASK_COUNT=4 ";
    command += stiction::testing::shell_quote(STICTION_BINARY);
    for (const auto& a : with({"--out", "sharded", "--keep", "all"})) {
      command += ' ';
      command += stiction::testing::shell_quote(a);
    }
    command += " & ";
  }
  command += "wait)";
  REQUIRE(std::system(command.c_str()) == 0);
  for (int k = 0; k < 4; ++k) {
    std::string shard = "sweep.shard-";
    shard += std::to_string(k);
    shard += ".csv";
    CHECK(fs::exists(dir / "sharded" / shard));
  }
  CHECK(read_table(dir / "sharded" / "sweep.shard-1.csv").rows.size() == 3);    // points 1, 5, 9
  CHECK(fs::exists(dir / "sharded" / "points" / "000009" / "trajectory.csv"));  // --keep all
  CHECK(fs::exists(dir / "sharded" / "points" / "000009" / "summary.json"));

  const Outcome merged = stiction::testing::run_stiction({"sweep", "--merge", "sharded"}, dir);
  INFO(merged.out);
  REQUIRE(merged.code == 0);
  CHECK_THAT(merged.out, Contains("10 points, every one exactly once"));
  const std::string whole = without_wall_time(dir / "whole" / "sweep.csv");
  CHECK(read_table(dir / "whole" / "sweep.csv").rows.size() == 10);
  CHECK(without_wall_time(dir / "sharded" / "sweep.csv") == whole);
  CHECK(fs::exists(dir / "sharded" / "sweep.png"));
  CHECK(stiction::testing::parse_svg(read_text(dir / "sharded" / "sweep.svg")).well_formed);

  // A missing shard, or a point twice, is refused.
  fs::rename(dir / "sharded" / "sweep.shard-2.csv", dir / "shard2.csv");
  Outcome bad = stiction::testing::run_stiction({"sweep", "--merge", "sharded"}, dir);
  CHECK(bad.code == 1);
  CHECK_THAT(bad.out, Contains("point 2 is missing"));
  fs::copy_file(dir / "sharded" / "sweep.shard-1.csv", dir / "sharded" / "sweep.shard-2.csv");
  bad = stiction::testing::run_stiction({"sweep", "--merge", "sharded"}, dir);
  CHECK(bad.code == 1);
  CHECK_THAT(bad.out, Contains("point 1 is in 2 shards"));

  // Resume: a table cut short mid-row keeps its complete rows and runs only the rest.
  std::string text = read_text(dir / "whole" / "sweep.csv");
  const std::size_t cut = text.find('\n', text.find('\n', text.find('\n') + 1) + 1);
  std::ofstream(dir / "whole" / "sweep.csv", std::ios::binary) << text.substr(0, cut + 12);
  const Outcome resumed = stiction::testing::run_stiction(
      {"sweep", "gen.toml", "--vary",
       "impedances.the_ground_contact_of_that_sphere.mu=0.2:0.8:5:log", "--vary",
       "bodies.a_sphere_with_a_rather_long_name_for_the_table.velocity[0]=0.3,0.6", "--out",
       "whole"},
      dir);
  INFO(resumed.out);
  CHECK(resumed.code == 0);
  CHECK_THAT(resumed.out, Contains("8 to run (2 done before)"));
  CHECK(without_wall_time(dir / "whole" / "sweep.csv") == whole);
}

TEST_CASE("sweep: a point gets the same verdict in any shard: its dynamics' first point is analysed") {
  // sphere_roll (v0 = 1 m/s) at mu = 0.0328 analysed on its own chatters at the scene's step (`run` warns);
  // at mu = 0.01, the sweep's first point, it does not. The two share their linear dynamics,
  // so the sweep takes the first point's analysis for both, and a shard that holds only the
  // second point must do the same (CI's Slurm array once tabled a note the unsharded sweep
  // did not have: each shard took its own first point's analysis).
  const fs::path dir = scratch("shared_verdict");
  const std::string second = "impedances.ground.mu=0.032819278725115";
  const Outcome alone =
      stiction::testing::run_stiction({"run", "sphere_roll", "--set", second, "--set", "bodies.sphere.velocity[0]=1",
                                       "--no-video", "--out", "alone"},
                                      dir);
  REQUIRE(alone.code == 0);
  REQUIRE_THAT(alone.out, Contains("where stuck friction chatters"));  // else the test shows nothing
  const std::vector<std::string> sweep{"sweep",     "sphere_roll",
                                       "--vary",    "impedances.ground.mu=0.01,0.032819278725115",
                                       "--set",     "bodies.sphere.velocity[0]=1",
                                       "--quiet",   "-j",
                                       "1"};
  auto with = [&](const std::vector<std::string>& extra) { return joined(sweep, extra); };
  REQUIRE(stiction::testing::run_stiction(with({"--out", "whole"}), dir).code == 0);
  // The second shard first: it meets point 1 before any other point.
  REQUIRE(stiction::testing::run_stiction(with({"--out", "sharded", "--shard", "1/2"}), dir).code == 0);
  REQUIRE(stiction::testing::run_stiction(with({"--out", "sharded", "--shard", "0/2"}), dir).code == 0);
  REQUIRE(stiction::testing::run_stiction({"sweep", "--merge", "sharded", "--quiet"}, dir).code == 0);
  CHECK(without_wall_time(dir / "sharded" / "sweep.csv") ==
        without_wall_time(dir / "whole" / "sweep.csv"));
}

TEST_CASE("sweep: an unstable point is a row with its suggestion, bad input exits 2") {
  const fs::path dir = scratch("unstable");
  const Outcome o =
      // --force-step: the step guard would refuse 4e-3 s (tests/ci/test_step_guard.cpp).
      stiction::testing::run_stiction({"sweep", "sphere_roll", "--vary", "simulation.dt=1e-4,4e-3",
                                       "--duration", "0.3", "--zip", "--out", "u", "--quiet",
                                       "--force-step"},
                                      dir);
  INFO(o.out);
  REQUIRE(o.code == 0);
  const Table t = read_table(dir / "u" / "sweep.csv");
  REQUIRE(t.rows.size() == 2);
  CHECK(t.rows[0][t.column("status")] == "ok");
  CHECK(t.rows[1][t.column("status")] == "unstable");
  CHECK(std::stod(t.rows[1][t.column("suggested_dt")]) < 4e-3);
  CHECK(fs::exists(dir / "u" / "points" / "000001" / "summary.json"));

  // A value the loader rejects at one point is that point's row, not the sweep's end.
  const Outcome rejected = stiction::testing::run_stiction(
      {"sweep", "sphere_roll", "--vary", "impedances.ground.mu=0.1,-1", "--duration", "0.05",
       "--out", "r", "--quiet"},
      dir);
  INFO(rejected.out);
  CHECK(rejected.code == 0);
  const std::string text = read_text(dir / "r" / "sweep.csv");
  CHECK_THAT(text, Contains("\n0,0.1,ok,"));
  CHECK_THAT(text, Contains("\n1,-1,error,,,,"));
  CHECK_THAT(text, Contains("impedances.ground.mu"));

  Outcome bad = stiction::testing::run_stiction(
      {"sweep", "sphere_roll", "--vary", "impedances.grund.mu=0.1,0.2", "--out", "b"}, dir);
  CHECK(bad.code == 2);
  CHECK_THAT(bad.out, Contains("grund"));
  bad = stiction::testing::run_stiction(
      {"sweep", "sphere_roll", "--vary", "impedances.ground.mu=0.1:0.2", "--out", "b"}, dir);
  CHECK(bad.code == 2);
  CHECK_THAT(bad.out, Contains("start:stop:count"));
  bad = stiction::testing::run_stiction(
      {"sweep", "sphere_roll", "--vary", "impedances.ground.mu=0.1,0.2", "--vary",
       "simulation.dt=1e-4", "--zip", "--out", "b"},
      dir);
  CHECK(bad.code == 2);
  bad =
      stiction::testing::run_stiction({"sweep", "sphere_roll", "--vary", "impedances.ground.mu=0.1",
                                       "--shard", "4/4", "--out", "b"},
                                      dir);
  CHECK(bad.code == 2);
}

TEST_CASE("sweep: a ball pushed until it slips never sticks: first_slip is tabled and plotted") {
  // A generated ball on a floor pushed at its centre by c t: rolling, the floor carries 2/7
  // of the push, so it slips when 2 c t / 7 = mu m g, at t = 3.5 mu m g / c.
  const fs::path dir = scratch("pushed");
  const double c = 7.3, g = 9.81;
  std::ostringstream s;
  s << "name = \"generated_pushed_ball\"\ngravity = [0.0, 0.0, " << -g << "]\n"
    << "[simulation]\ndt = 1e-4\nduration = 3.0\noutput_rate = 100.0\n"
    << "[bodies.pushed_ball]\ntype = \"rigid_body\"\nmass = 1.0\nshape = \"sphere\"\n"
    << "radius = 0.13\nposition = [0.0, 0.0, 0.13]\n"
    << "[impedances.floor_under_the_ball]\ntype = \"kikuuwe_contact\"\nbody = \"pushed_ball\"\n"
    << "stiffness = 1e6\ndamping = 300.0\nmu = 0.2\nsettle = true\n"
    << "[impedances.push]\ntype = \"force_source\"\nbody = \"pushed_ball\"\n"
    << "force = [\"" << c << "*t\", \"0\", \"0\"]\n";
  std::ofstream(dir / "pushed.toml") << s.str();
  const Outcome o = stiction::testing::run_stiction(
      {"sweep", "pushed.toml", "--vary", "impedances.floor_under_the_ball.mu=0.1:0.3:3", "--vary",
       "bodies.pushed_ball.mass=0.5,1.5", "--keep", "none", "--out", "sweep"},
      dir);
  INFO(o.out);
  REQUIRE(o.code == 0);
  const Table t = read_table(dir / "sweep" / "sweep.csv");
  REQUIRE(t.rows.size() == 6);
  for (const auto& row : t.rows) {
    const double mu = std::stod(row[t.column("impedances.floor_under_the_ball.mu")]);
    const double m = std::stod(row[t.column("bodies.pushed_ball.mass")]);
    INFO("mu = " << mu << ", m = " << m);
    CHECK(row[t.column("floor_under_the_ball.stick_time")].empty());
    CHECK(row[t.column("floor_under_the_ball.last_stick")].empty());
    // Located within a step of the closed form.
    CHECK(std::abs(std::stod(row[t.column("floor_under_the_ball.first_slip")]) -
                   3.5 * mu * m * g / c) <= 1.01e-4);
  }
  // The figure shows the first slips, not the empty stick times.
  const std::string md = read_text(dir / "sweep" / "sweep.md");
  CHECK_THAT(md, Contains("plot `floor_under_the_ball.first_slip` against"));
  CHECK_FALSE(md.find("`floor_under_the_ball.stick_time`") != std::string::npos);
  CHECK(fs::file_size(dir / "sweep" / "sweep.png") > 1000);
}
