#include "loop_cost.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>
#include <vector>

#include "components/admittance/planar_arm.hpp"
#include "core/integrator.hpp"
#include "core/simulation.hpp"
#include "scene/scene.hpp"

namespace stiction::bench {
namespace {

// This thread's CPU time: on a shared machine, time spent descheduled does not count.
struct Clock {
  using time_point = double;
  static double now() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  }
};

double seconds_since(double start) { return Clock::now() - start; }

// The least of the repeats: on a shared machine every other process only adds time, so the
// minimum is the closest to the code's own cost.
double best(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

// The median of the per-repeat ratios a[r] / b[r] (each repeat's three runs are adjacent in
// time, so a load that comes and goes hits them alike).
double median_ratio(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> r;
  for (std::size_t i = 0; i < a.size(); ++i) r.push_back(a[i] / b[i]);
  std::sort(r.begin(), r.end());
  const std::size_t n = r.size();
  return n % 2 == 1 ? r[n / 2] : 0.5 * (r[n / 2 - 1] + r[n / 2]);
}

// n spheres of different radii, launched at different speeds on one ground, each with its
// own contact: the network grows with n, the loop's per-row work too.
scene::Scene many_spheres(int n, double duration) {
  std::ostringstream s;
  s << "name = \"spheres_" << n << "\"\n[simulation]\ndt = 1e-4\nduration = " << duration
    << "\noutput_rate = 1000.0\n";
  for (int i = 0; i < n; ++i) {
    const double r = 0.1 + 0.002 * i;
    s << "[bodies.s" << i
      << "]\ntype = \"rigid_body\"\nmass = 0.3\nshape = \"sphere\"\nradius = " << r
      << "\nposition = [" << i << ".0, 0.0, " << 1.01 * r << "]\nvelocity = [" << 1.0 + 0.01 * i
      << ", 0.0, 0.0]\n";
    s << "[impedances.c" << i << "]\ntype = \"kikuuwe_contact\"\nbody = \"s" << i
      << "\"\nnormal = [0.0, 0.0, 1.0]\nstiffness = 1e7\ndamping = 10.0\nmu = 0.1\n";
  }
  return scene::build_scene(toml::parse(s.str()), "spheres.toml");
}

class DiscardRows final : public core::RowSink {
 public:
  void write(const double*, std::size_t, std::size_t) override {}
};

void loop_ratio(const char* label, scene::Scene& scene, int repeats) {
  core::Network& net = *scene.network;
  const double T = scene.run.dt;
  std::vector<double> bare, in_memory, streamed;
  long steps = 0;
  for (int r = 0; r < repeats; ++r) {
    core::RungeKuttaStepper stepper(core::rk4_tableau(), net.state_dim());
    core::Vec x = net.initial_state();
    steps = static_cast<long>(std::ceil(scene.run.duration / T - 1e-9));
    auto start = Clock::now();
    for (long k = 0; k < steps; ++k) {
      stepper.step(net, k * T, T, x);
      net.project(x);
    }
    bare.push_back(seconds_since(start));
    start = Clock::now();
    const core::RunResult a = core::simulate(net, scene.run);
    in_memory.push_back(seconds_since(start));
    DiscardRows none;
    start = Clock::now();
    const core::RunResult b = core::simulate(net, scene.run, {}, &none);
    streamed.push_back(seconds_since(start));
    if (a.steps != steps || b.steps != steps)
      std::fprintf(stderr, "%s: step counts differ\n", label);
  }
  const double step_us = best(bare) / static_cast<double>(steps) * 1e6;
  std::printf(
      "%-28s bare step %.2f us; simulate / bare step: %.3f (rows in memory), %.3f (rows "
      "streamed to a sink); median of %d repeats: %.3f, %.3f\n",
      label, step_us, best(in_memory) / best(bare), best(streamed) / best(bare), repeats,
      median_ratio(in_memory, bare), median_ratio(streamed, bare));
}

// Least-squares slope of log(time) against log(n).
double exponent(const std::vector<int>& n, const std::vector<double>& t) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double m = static_cast<double>(n.size());
  for (std::size_t i = 0; i < n.size(); ++i) {
    const double x = std::log(n[i]), y = std::log(t[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (m * sxy - sx * sy) / (m * sxx - sx * sx);
}

}  // namespace

void print_loop_ratios() {
  scene::Scene sphere = scene::load_scene("sphere_roll");
  loop_ratio("sphere_roll (1 kHz rows)", sphere, 9);
  scene::Scene spheres = many_spheres(100, 0.2);
  loop_ratio("100 spheres (1 kHz rows)", spheres, 5);
}

void print_arm_exponents() {
  const std::vector<int> sizes{8, 16, 32, 64};
  std::vector<double> aba_ns, matrix_ns;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-1.0, 1.0);
  for (int n : sizes) {
    components::PlanarArmParams p;
    for (int i = 0; i < n; ++i) p.links.push_back(components::box_link(0.2, 0.02, 0.2));
    const components::PlanarArm arm("arm", p);
    core::Vec x(2 * n), u = core::Vec::Zero(n), x_dot(2 * n);
    for (int i = 0; i < 2 * n; ++i) x[i] = angle(rng);
    Eigen::MatrixXd H(n, n);
    core::Vec c(n), rhs(n);
    Eigen::LLT<Eigen::MatrixXd> llt(n);
    const long calls = std::max(200L, 400000L / n);
    std::vector<double> a, m;
    for (int r = 0; r < 9; ++r) {
      auto start = Clock::now();
      for (long k = 0; k < calls; ++k) {
        arm.derivative(x, u, x_dot);
        x[0] += 1e-12 * x_dot[n];  // a dependency, so the calls are not hoisted
      }
      a.push_back(seconds_since(start) / calls * 1e9);
      start = Clock::now();
      for (long k = 0; k < calls / 4; ++k) {
        arm.dynamics(x.head(n), x.tail(n), H, c);
        rhs = u - c;
        llt.compute(H);
        llt.solveInPlace(rhs);
        x[0] += 1e-12 * rhs[0];
      }
      m.push_back(seconds_since(start) / (calls / 4) * 1e9);
    }
    aba_ns.push_back(best(a));
    matrix_ns.push_back(best(m));
  }
  std::printf("planar_arm forward dynamics, ns per evaluation at n =");
  for (int n : sizes) std::printf(" %d", n);
  std::printf("\n  articulated-body (O(n)):");
  for (double t : aba_ns) std::printf(" %.0f", t);
  std::printf("   exponent over n = 8..64: %.2f\n  mass matrix + Cholesky:  ",
              exponent(sizes, aba_ns));
  for (double t : matrix_ns) std::printf(" %.0f", t);
  std::printf("   exponent over n = 8..64: %.2f\n", exponent(sizes, matrix_ns));
}

}  // namespace stiction::bench
