#include "services/step_check.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <sstream>

#include "services/pilot.hpp"
#include "scene/external_elements.hpp"
#include "services/step_check_cache.hpp"
#include "core/stability.hpp"
#include "sys/interrupt.hpp"
#include "text/number_text.hpp"

namespace stiction::services {
namespace {

// The analysis starts this far below the smaller of the run's and the pilot's step: a limit
// further below is reported as "below lowest_step", which is all a guard needs to know, and
// the grid points below it (each linearizes every sampled state) are not paid for.
constexpr double kLowestStepRatio = 1.0 / 32.0;

// What the analysis depends on, as text (StepCheckCache compares it in full).
std::string cache_key(const scene::Scene& scene, const core::RunOptions& pilot) {
  std::ostringstream key;
  key.precision(17);
  key << "step_check 1\n"
      << scene.path.string() << "\n"
      << pilot.integrator << " dt " << pilot.dt << " duration " << pilot.duration << " of "
      << scene.run.duration << " energy " << scene.run.energy_tolerance << "\n"
      << scene.document;
  // Elements supplied in code, by their fingerprints (check_step caches only when all have
  // one).
  if (scene.externals != nullptr) {
    for (const auto& [name, text] : scene.externals->fingerprints) {
      key << "\nexternal " << name << " " << text;
    }
  }
  return key.str();
}

nlohmann::json to_cache(const StepCheck& c) {
  return {{"unbounded", c.unbounded},           {"instability_limit", c.instability_limit},
          {"chatter_limit", c.chatter_limit},   {"limiting_time", c.limiting_time},
          {"pilot_duration", c.pilot_duration}, {"pilot_shortened", c.pilot_shortened}};
}

bool from_cache(const nlohmann::json& j, StepCheck& c) {
  try {
    c.unbounded = j.at("unbounded").get<bool>();
    c.instability_limit = j.at("instability_limit").get<double>();
    c.chatter_limit = j.at("chatter_limit").get<double>();
    c.limiting_time = j.at("limiting_time").get<double>();
    c.pilot_duration = j.at("pilot_duration").get<double>();
    c.pilot_shortened = j.at("pilot_shortened").get<bool>();
    return true;
  } catch (const nlohmann::json::exception&) {
    return false;
  }
}

}  // namespace

std::string StepCheck::verdict() const {
  if (!applies || skipped) return "not_checked";
  if (!unbounded && dt > instability_limit) return trial_confirmed ? "ok" : "unstable";
  if (dt > chatter_limit) return trial_confirmed ? "ok" : "chatter";
  return "ok";
}

std::string StepCheck::reason() const {
  if (!applies) return integrator + " chooses its steps from its tolerance";
  if (skipped) {
    return "the network's largest island (bodies its elements couple) has " +
           std::to_string(island_states) + " states, more than the " + std::to_string(core::kMaxAnalysedStates) +
           " the step analysis linearizes (docs/limits.md); the step was not checked";
  }
  return "";
}

double StepCheck::safe_step() const {
  const double limit = std::min(instability_limit, chatter_limit);
  return 0.8 * (limit > 0.0 ? limit : lowest_step);
}

StepCheck check_step(scene::Scene& scene) {
  StepCheck c;
  c.integrator = scene.run.integrator;
  c.dt = scene.run.dt;
  if (!core::integrator_traits(c.integrator).step_analysed()) {
    c.applies = false;  // an adaptive integrator: its step follows its tolerance
    return c;
  }
  c.states = scene.network->state_dim();
  c.island_states = core::largest_island_states(*scene.network);
  if (!core::analysable(*scene.network)) {
    c.skipped = true;  // bounded work (issue 25): no pilot, no linearization
    return c;
  }
  core::RunOptions pilot_run = scene.run;
  pilot_run.dt = std::min(scene.run.dt, scene.authored_dt);
  const Pilot pilot = bounded_pilot(*scene.network, pilot_run);
  c.pilot_dt = pilot_run.dt;
  c.pilot_duration = pilot.options.duration;
  c.pilot_shortened = pilot.shortened;
  c.lowest_step = kLowestStepRatio * pilot_run.dt;

  const StepCheckCache cache(cache_key(scene, pilot.options));
  // Elements supplied in code (Python laws) are not in the document: the key holds their
  // fingerprints, and a scene with one that has none is not cached.
  const bool cacheable = scene.externals == nullptr || scene.externals->fingerprinted();
  if (const auto hit = cacheable ? cache.load() : std::nullopt; hit && from_cache(*hit, c)) {
    c.cached = true;
    return c;
  }
  const auto start = std::chrono::steady_clock::now();
  const auto states = core::sample_states(*scene.network, pilot.options, kStatesPerRegime);
  if (sys::interrupted()) throw sys::Interrupted{};
  const core::StepLimit limit = core::predict_step_limit(
      *scene.network, c.integrator, states, c.lowest_step, kMaxAnalysedStep, &sys::interrupt_flag());
  if (limit.interrupted || sys::interrupted()) throw sys::Interrupted{};
  const StepCheck found = step_check_from(limit, c.integrator, c.dt, c.lowest_step);
  c.unbounded = found.unbounded;
  c.instability_limit = found.instability_limit;
  c.chatter_limit = found.chatter_limit;
  c.limiting_time = found.limiting_time;
  c.analysis_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (cacheable) cache.store(to_cache(c));
  return c;
}

SharedStepChecks::SharedStepChecks(std::function<scene::Scene(std::size_t)> load)
    : load_(std::move(load)) {}

std::size_t SharedStepChecks::representative(const DynamicsFingerprint& fingerprint,
                                             std::size_t point) {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& [known, first] : firsts_) {
    if (known == fingerprint) return first;
  }
  // Points below `point` not yet fingerprinted: the first of them with this fingerprint
  // represents it. Each point is loaded here at most once per process.
  for (; scanned_ < point; ++scanned_) {
    try {
      scene::Scene earlier = load_(scanned_);
      DynamicsFingerprint f = dynamics_fingerprint(earlier);
      const bool match = f == fingerprint;
      bool known = false;
      for (const auto& entry : firsts_) known = known || entry.first == f;
      if (!known) firsts_.emplace_back(std::move(f), scanned_);
      if (match) return scanned_++;
    } catch (const std::exception&) {
      // A point that does not load (its row says why) represents nothing.
    }
  }
  if (scanned_ == point) {
    firsts_.emplace_back(fingerprint, point);
    ++scanned_;
  }
  return point;
}

StepCheck SharedStepChecks::check(scene::Scene& scene, std::size_t point) {
  const std::size_t first = representative(dynamics_fingerprint(scene), point);
  std::promise<StepCheck> promise;
  std::shared_future<StepCheck> analysis;
  bool mine = false;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto found = analyses_.find(first);
    if (found != analyses_.end()) {
      analysis = found->second;
    } else {
      analysis = promise.get_future().share();
      analyses_.emplace(first, analysis);
      mine = true;
    }
  }
  if (mine) {
    try {
      if (first == point) {
        promise.set_value(check_step(scene));
      } else {
        scene::Scene represented = load_(first);
        promise.set_value(check_step(represented));
      }
    } catch (...) {
      promise.set_exception(std::current_exception());  // the waiters see it too
    }
  }
  StepCheck c = analysis.get();  // rethrows sys::Interrupted from the analysing thread
  if (first == point) return c;
  c.dt = scene.run.dt;
  c.shared = true;
  c.cached = false;
  c.analysis_seconds = 0.0;
  return c;
}

StepCheck step_check_from(const core::StepLimit& limit, const std::string& integrator, double dt,
                          double lowest_step) {
  StepCheck c;
  c.integrator = integrator;
  c.dt = dt;
  c.lowest_step = lowest_step;
  c.unbounded = limit.unbounded;
  c.instability_limit = limit.max_step;
  c.chatter_limit = std::min(limit.chatter_free_step, limit.max_step);
  c.limiting_time = limit.limiting_time;
  return c;
}

nlohmann::ordered_json step_check_json(const StepCheck& c) {
  nlohmann::ordered_json j;
  j["integrator"] = c.integrator;
  j["dt"] = c.dt;
  j["verdict"] = c.verdict();
  if (!c.applies || c.skipped) {
    j["reason"] = c.reason();
    if (c.skipped) {
      j["states"] = c.states;
      j["largest_island_states"] = c.island_states;
      j["max_states"] = core::kMaxAnalysedStates;
    }
    return j;
  }
  const auto limit_or_null = [&](double v) {
    return v > 0.0 ? nlohmann::ordered_json(v) : nlohmann::ordered_json();
  };
  j["instability_limit"] =
      c.unbounded ? nlohmann::ordered_json() : limit_or_null(c.instability_limit);
  j["unbounded"] = c.unbounded;
  j["chatter_limit"] = limit_or_null(c.chatter_limit);
  j["lowest_step_analysed"] = c.lowest_step;
  // How far below each limit the step is: limit / dt (> 1: inside).
  j["margin"] =
      c.unbounded ? nlohmann::ordered_json() : nlohmann::ordered_json(c.instability_limit / c.dt);
  j["chatter_margin"] = c.chatter_limit / c.dt;
  j["limiting_time"] = c.limiting_time;
  j["forced"] = c.forced;
  j["confirmed_by_trial"] = c.trial_confirmed;
  if (!c.trial.empty()) j["trial"] = c.trial;
  j["pilot"] = {
      {"dt", c.pilot_dt}, {"duration", c.pilot_duration}, {"shortened", c.pilot_shortened}};
  j["analysis_seconds"] = c.analysis_seconds;
  j["cached"] = c.cached;
  j["shared"] = c.shared;
  return j;
}

std::string step_check_text(const StepCheck& c) {
  char text[400];
  const std::string verdict = c.verdict();
  const std::string dt = text::shortest(c.dt);  // the scene's step, as given
  if (verdict == "unstable") {
    if (c.instability_limit > 0.0) {
      std::snprintf(text, sizeof text,
                    "dt = %s s is above %s's predicted instability limit %.3g s on this scene "
                    "(limiting state at t = %.3g s)",
                    dt.c_str(), c.integrator.c_str(), c.instability_limit, c.limiting_time);
    } else {
      std::snprintf(text, sizeof text,
                    "dt = %s s: %s is predicted unstable on this scene at every step down to "
                    "%.3g s (limiting state at t = %.3g s)",
                    dt.c_str(), c.integrator.c_str(), c.lowest_step, c.limiting_time);
    }
  } else if (verdict == "chatter") {
    std::snprintf(text, sizeof text,
                  "dt = %s s is above the step %.3g s where stuck friction chatters under %s "
                  "on this scene (stable up to %.3g s, but sticks may come late or not at all)",
                  dt.c_str(), c.chatter_limit, c.integrator.c_str(), c.instability_limit);
  } else if (verdict == "ok" && c.trial_confirmed) {
    const bool past_instability = !c.unbounded && c.dt > c.instability_limit;
    std::snprintf(text, sizeof text,
                  "dt = %s s is above %s's predicted %s %.3g s on this scene, but a trial at "
                  "this step ran stable and accurate",
                  dt.c_str(), c.integrator.c_str(),
                  past_instability ? "instability limit" : "step where stuck friction chatters",
                  past_instability ? c.instability_limit : c.chatter_limit);
  } else if (verdict == "ok") {
    std::snprintf(text, sizeof text, "dt = %s s is below %s's predicted limits on this scene",
                  dt.c_str(), c.integrator.c_str());
  } else if (c.skipped) {
    return c.reason();
  } else {
    std::snprintf(text, sizeof text, "%s: no fixed step to check", c.integrator.c_str());
  }
  return text;
}

}  // namespace stiction::services
