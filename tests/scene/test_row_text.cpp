// The row path's text (issue 36 item 4): io::format_number, io::RowText and io::CsvStream
// (a writer thread behind io::BlockPipe) write exactly the bytes of the reference below,
// which is the formatting trajectory.csv had before them (DESIGN section 4).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include <catch2/catch.hpp>

#include "core/simulation.hpp"
#include "io/atomic_file.hpp"
#include "io/block_pipe.hpp"
#include "io/csv_writer.hpp"
#include "io/row_text.hpp"
#include "scene/scene.hpp"

using namespace stiction;
namespace fs = std::filesystem;

namespace {

// The reference: std::to_chars' shortest text, ".0" after a bare integer.
std::string reference_number(double v) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  std::string out(buffer, result.ptr);
  if (std::find_if(buffer, result.ptr, [](char c) { return c != '-' && (c < '0' || c > '9'); }) ==
      result.ptr) {
    out += ".0";
  }
  return out;
}

std::string reference_csv(const std::vector<std::string>& columns, const std::vector<double>& rows) {
  std::string out;
  for (std::size_t c = 0; c < columns.size(); ++c) out += (c > 0 ? "," : "") + columns[c];
  out += '\n';
  for (std::size_t i = 0; i < rows.size(); ++i) {
    out += reference_number(rows[i]);
    out += (i + 1) % columns.size() == 0 ? '\n' : ',';
  }
  return out;
}

std::string number_text(double v) {
  char buffer[io::kMaxNumberChars];
  return std::string(buffer, io::format_number(buffer, v));
}

double from_bits(std::uint64_t bits) {
  double v;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

// Values of every kind: any bit pattern (subnormals, NaNs, huge and tiny exponents), whole
// numbers, short decimals, powers of ten and the edges.
std::vector<double> awkward_values(std::size_t count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::vector<double> v = {0.0,
                           -0.0,
                           1.0,
                           -1.0,
                           12.0,
                           1e15,
                           1e16,
                           1e17,
                           123456789012345678.0,
                           9007199254740993.0,
                           0.1,
                           1e-7,
                           1.5e-7,
                           1e20,
                           1e21,
                           1e22,
                           1e23,
                           std::numeric_limits<double>::denorm_min(),
                           -std::numeric_limits<double>::denorm_min(),
                           std::numeric_limits<double>::min(),
                           -std::numeric_limits<double>::min(),
                           2.2250738585072009e-308,
                           std::numeric_limits<double>::max(),
                           -std::numeric_limits<double>::max(),
                           std::numeric_limits<double>::epsilon(),
                           std::numeric_limits<double>::infinity(),
                           -std::numeric_limits<double>::infinity(),
                           std::numeric_limits<double>::quiet_NaN(),
                           -std::numeric_limits<double>::quiet_NaN(),
                           // whole numbers as long fixed as with an exponent: the longest text
                           -2139563737866039721984.0,
                           -1e21 - 65536.0,
                           9.999999999999999e21};
  for (int e = -330; e <= 310; ++e) v.push_back(std::pow(10.0, e));
  std::uniform_int_distribution<int> kind(0, 4);
  std::uniform_int_distribution<long long> whole(-(1LL << 54), 1LL << 54);
  std::uniform_int_distribution<int> digits(-99999, 99999);
  std::uniform_int_distribution<int> exponent(-12, 12);
  std::uniform_int_distribution<std::uint64_t> subnormal(1, (std::uint64_t{1} << 52) - 1);
  while (v.size() < count) {
    switch (kind(rng)) {
      case 0: v.push_back(from_bits(rng())); break;  // anything, NaN payloads included
      case 1: v.push_back(static_cast<double>(whole(rng) >> (rng() % 54))); break;
      case 2: v.push_back(digits(rng) * std::pow(10.0, exponent(rng))); break;
      case 3: v.push_back(from_bits(subnormal(rng) | (rng() & (std::uint64_t{1} << 63)))); break;
      default: v.push_back(std::ldexp(static_cast<double>(rng() >> 11), 500 - static_cast<int>(rng() % 1100)));
    }
  }
  return v;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("stiction_row_text_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

}  // namespace

TEST_CASE("row text: every number as the reference writes it") {
  const std::vector<double> values = awkward_values(200000, 36);
  std::size_t differ = 0;
  for (double v : values) {
    const std::string text = number_text(v);
    if (text != reference_number(v)) {
      if (++differ < 5) FAIL_CHECK(text << " != " << reference_number(v));
    }
    CHECK(text.size() <= io::kMaxNumberChars);
  }
  CHECK(differ == 0);
  CHECK(number_text(-0.0) == "-0.0");
  CHECK(number_text(0.0) == "0.0");
  CHECK(number_text(1e16) == "1e+16");
  CHECK(number_text(std::numeric_limits<double>::denorm_min()) == "5e-324");
  CHECK(number_text(-2139563737866039721984.0) == "-2139563737866039721984.0");  // 25 characters
}

TEST_CASE("row text: rows with repeated cells equal the reference") {
  // Columns that hold still, change sign of zero, become NaN and stay NaN, or change every row.
  const std::vector<double> pool = awkward_values(5000, 7);
  std::mt19937_64 rng(11);
  const std::size_t columns = 9;
  std::vector<double> rows;
  std::vector<double> row(columns, 0.0);
  for (int r = 0; r < 4000; ++r) {
    for (std::size_t c = 0; c < columns; ++c) {
      if (rng() % (c + 1) == 0) row[c] = pool[rng() % pool.size()];
      if (c == 0) row[c] = r % 2 == 0 ? 0.0 : -0.0;  // equal values, different text
    }
    rows.insert(rows.end(), row.begin(), row.end());
  }
  const std::vector<std::string> names(columns, "c");
  io::RowText text(columns);
  io::TextBuffer out;
  out.append(reference_csv(names, {}));
  for (std::size_t r = 0; r < rows.size() / columns; ++r) text.append_row(out, &rows[r * columns]);
  CHECK(std::string(out.view()) == reference_csv(names, rows));
  CHECK(text.converted() < rows.size());  // some cells were copied, not formatted again
}

TEST_CASE("row text: CsvStream's writer thread writes the reference bytes, whatever the blocks") {
  const fs::path dir = fresh_dir("stream");
  const std::vector<double> pool = awkward_values(3000, 3);
  const std::vector<std::string> names = {"t", "a.x", "a.y", "b"};
  std::vector<double> rows;
  // More rows than the ring holds (16 blocks of 256), ending inside a block.
  for (int r = 0; r < 16 * 256 * 2 + 77; ++r) {
    rows.push_back(r * 1e-3);
    rows.push_back(pool[static_cast<std::size_t>(r) % pool.size()]);
    rows.push_back(r % 3 == 0 ? 1.0 : 0.5);
    rows.push_back(pool[static_cast<std::size_t>(r * 7) % pool.size()]);
  }
  {
    io::CsvStream stream(dir / "trajectory.csv", names);
    std::size_t at = 0, step = 1;
    const std::size_t total = rows.size() / names.size();
    while (at < total) {  // pushes of 1, 2, 3, ... rows
      const std::size_t n = std::min(step++ % 700, total - at);
      stream.write(&rows[at * names.size()], n, names.size());
      at += n;
    }
    CHECK_FALSE(fs::exists(dir / "trajectory.csv"));  // complete or absent
    stream.commit();
  }
  CHECK(slurp(dir / "trajectory.csv") == reference_csv(names, rows));
  fs::remove_all(dir);
}

TEST_CASE("row text: an abandoned CsvStream leaves no file and no temporary") {
  const fs::path dir = fresh_dir("abandoned");
  std::vector<double> rows(3 * 5000, 0.25);
  {
    io::CsvStream stream(dir / "trajectory.csv", {"t", "x", "y"});
    stream.write(rows.data(), 5000, 3);  // the writer is busy with these when it is dropped
  }
  CHECK(fs::is_empty(dir));
  fs::remove_all(dir);
}

TEST_CASE("row text: the writer thread's failure surfaces in the producing thread") {
  SECTION("at a later push") {
    int consumed = 0;
    io::BlockPipe pipe(
        2,
        [&](const double*, std::size_t) {
          ++consumed;
          throw io::IoError("disk full");
        },
        4, 8);
    const std::vector<double> rows(2 * 8, 1.0);
    // One full block fails the writer; a later push (or the close) must say so.
    bool thrown = false;
    try {
      for (int i = 0; i < 100; ++i) pipe.push(rows.data(), 8);
      pipe.close();
    } catch (const io::IoError& e) {
      thrown = std::string(e.what()) == "disk full";
    }
    CHECK(thrown);
    CHECK(consumed == 1);  // the writer stopped at its first failure
  }
  SECTION("at close") {
    io::BlockPipe pipe(
        1, [](const double*, std::size_t) { throw std::runtime_error("no room"); }, 4, 8);
    const double v = 1.0;
    pipe.push(&v, 1);  // a partial block: handed over by close()
    CHECK_THROWS_WITH(pipe.close(), "no room");
  }
  SECTION("nothing lost, in order, with tiny blocks") {
    std::vector<double> seen;
    io::BlockPipe pipe(
        1, [&](const double* rows, std::size_t n) { seen.insert(seen.end(), rows, rows + n); }, 2,
        3);
    std::vector<double> rows(1000);
    for (std::size_t i = 0; i < rows.size(); ++i) rows[i] = static_cast<double>(i);
    for (std::size_t i = 0; i < rows.size(); i += 7)
      pipe.push(&rows[i], std::min<std::size_t>(7, rows.size() - i));
    pipe.close();
    CHECK(seen == rows);
  }
}

TEST_CASE("row text: a whole run's trajectory.csv equals the reference text of its rows") {
  // sphere_roll under two integrators (rows at step ends, between steps, from dense output),
  // the rows kept in memory against the same run streamed through CsvStream.
  for (const char* integrator : {"rk4", "implicit", "rk4_adaptive"}) {
    CAPTURE(integrator);
    const std::vector<std::string> sets = {
        std::string("simulation.integrator=\"") + integrator + "\"",
        "simulation.duration=0.7",
        std::string(integrator) == "implicit" ? "simulation.dt=0.004" : "simulation.dt=1e-4",
        std::string(integrator) == "rk4_adaptive" ? "simulation.tolerance=1e-6"
                                                  : "simulation.output_rate=1000.0"};
    scene::Scene in_memory = scene::load_scene("sphere_roll", sets);
    const core::RunResult whole = core::simulate(*in_memory.network, in_memory.run);
    REQUIRE(whole.rows > 600);
    const auto& columns = whole.trajectory.columns();
    std::vector<double> rows;
    for (int r = 0; r < whole.trajectory.row_count(); ++r)
      rows.insert(rows.end(), whole.trajectory.row(r), whole.trajectory.row(r) + columns.size());

    const fs::path dir = fresh_dir(integrator);
    scene::Scene streamed = scene::load_scene("sphere_roll", sets);
    {
      io::CsvStream stream(dir / "trajectory.csv", columns);
      const core::RunResult run = core::simulate(*streamed.network, streamed.run, {}, &stream);
      stream.commit();
      CHECK(run.rows == whole.rows);
      CHECK(run.row_seconds > 0.0);
    }
    CHECK(slurp(dir / "trajectory.csv") == reference_csv(columns, rows));
    fs::remove_all(dir);
  }
}
