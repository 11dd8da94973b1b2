// The run loop's streaming (issue 14) and its slip detection from the step's own evaluation
// (issue 13): rows sent to a sink equal the rows kept in memory, trajectory.csv streamed
// equals the one written at the end, the thinned copy keeps evenly spaced rows within its
// bound, and the slips the network captures during a step equal the maps' evaluation.
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "core/row_sink.hpp"
#include "io/csv_writer.hpp"
#include "sphere_fixture.hpp"

using namespace stiction;

namespace {

class CollectRows final : public core::RowSink {
 public:
  explicit CollectRows(std::vector<std::string> columns) : trajectory(std::move(columns)) {}
  void write(const double* rows, std::size_t count, std::size_t columns) override {
    for (std::size_t r = 0; r < count; ++r) trajectory.append(rows + r * columns);
    ++blocks;
  }
  void finish() override { finished = true; }
  core::Trajectory trajectory;
  int blocks = 0;
  bool finished = false;
};

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

testing::SphereCase random_sphere(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  testing::SphereCase c;
  c.mass = 0.1 + u(rng);
  c.radius = 0.05 + 0.3 * u(rng);
  c.height = 1.01 * c.radius;
  c.mu = 0.1 + 0.4 * u(rng);
  c.v0 = 0.5 + 2.0 * u(rng);
  return c;
}

}  // namespace

TEST_CASE("streaming: rows sent to a sink equal the rows kept in memory, events too") {
  std::mt19937 rng(31);
  for (int trial = 0; trial < 3; ++trial) {
    const testing::SphereCase c = random_sphere(rng);
    core::RunOptions options;
    options.duration = 0.37;
    options.output_rate = 700.0 + 300.0 * trial;  // not a divisor of the step rate
    auto a = testing::make_sphere(c);
    const core::RunResult in_memory = core::simulate(*a, options);
    auto b = testing::make_sphere(c);
    std::vector<std::string> columns{"t"};
    for (auto& s : b->signal_columns()) columns.push_back(s);
    CollectRows sink(columns);
    const core::RunResult streamed = core::simulate(*b, options, {}, &sink);

    CHECK(sink.finished);
    CHECK(sink.blocks >= in_memory.trajectory.row_count() / 256);
    REQUIRE(sink.trajectory.row_count() == in_memory.trajectory.row_count());
    CHECK(streamed.rows == in_memory.trajectory.row_count());
    for (int r = 0; r < in_memory.trajectory.row_count(); ++r) {
      for (int col = 0; col < in_memory.trajectory.column_count(); ++col) {
        REQUIRE(sink.trajectory.at(r, col) == in_memory.trajectory.at(r, col));
      }
    }
    // The result keeps the last row only (the summary's final values).
    REQUIRE(streamed.trajectory.row_count() == 1);
    const int last = in_memory.trajectory.row_count() - 1;
    for (int col = 0; col < in_memory.trajectory.column_count(); ++col) {
      CHECK(streamed.trajectory.at(0, col) == in_memory.trajectory.at(last, col));
    }
    REQUIRE(streamed.slip_events.size() == 1);
    const auto& ea = in_memory.slip_events[0].monitor.events();
    const auto& eb = streamed.slip_events[0].monitor.events();
    REQUIRE(ea.size() == eb.size());
    for (std::size_t i = 0; i < ea.size(); ++i) {
      CHECK(ea[i].kind == eb[i].kind);
      CHECK(ea[i].time == eb[i].time);
    }
  }
}

TEST_CASE("streaming: the thinned copy keeps evenly spaced rows within its bound") {
  for (std::size_t total : {10u, 999u, 1000u, 1001u, 123457u}) {
    core::DecimatedTrajectory thin({"t", "v"}, 1000);
    std::vector<double> block;
    for (std::size_t r = 0; r < total; ++r) {
      block.push_back(static_cast<double>(r));
      block.push_back(2.0 * static_cast<double>(r));
      if (block.size() == 2 * 77 || r + 1 == total) {  // blocks of odd size
        thin.write(block.data(), block.size() / 2, 2);
        block.clear();
      }
    }
    thin.finish();
    const core::Trajectory& t = thin.trajectory();
    INFO("rows " << total << ", stride " << thin.stride());
    CHECK(t.row_count() <= 1001);
    CHECK(t.at(0, 0) == 0.0);
    CHECK(t.at(t.row_count() - 1, 0) == static_cast<double>(total - 1));  // the last row
    const double stride = static_cast<double>(thin.stride());
    CHECK(total <= 1000 * thin.stride());
    for (int r = 0; r + 1 < t.row_count(); ++r) {
      CHECK(t.at(r, 0) == r * stride);
      CHECK(t.at(r, 1) == 2.0 * t.at(r, 0));
    }
    if (total <= 1000) CHECK(static_cast<std::size_t>(t.row_count()) == total);
  }
}

TEST_CASE("streaming: trajectory.csv written row by row equals the one written at once") {
  const testing::SphereCase c;
  auto net = testing::make_sphere(c);
  core::RunOptions options;
  options.duration = 0.3;
  const core::RunResult result = core::simulate(*net, options);
  const auto dir =
      std::filesystem::temp_directory_path() / ("stiction_stream_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  io::write_csv(result.trajectory, dir / "whole.csv");
  {
    io::CsvStream stream(dir / "streamed.csv", result.trajectory.columns());
    for (int r = 0; r < result.trajectory.row_count(); r += 3) {
      const int n = std::min(3, result.trajectory.row_count() - r);
      stream.write(result.trajectory.row(r), static_cast<std::size_t>(n),
                   static_cast<std::size_t>(result.trajectory.column_count()));
    }
    CHECK_FALSE(std::filesystem::exists(dir / "streamed.csv"));  // complete or absent
    stream.commit();
  }
  CHECK(read_text(dir / "streamed.csv") == read_text(dir / "whole.csv"));
  {
    io::CsvStream abandoned(dir / "abandoned.csv", result.trajectory.columns());
    abandoned.write(result.trajectory.row(0), 1, result.trajectory.column_count());
  }
  CHECK_FALSE(std::filesystem::exists(dir / "abandoned.csv"));
  std::size_t leftovers = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    leftovers += e.path().filename().string()[0] == '.';
  CHECK(leftovers == 0);
  std::filesystem::remove_all(dir);
}
