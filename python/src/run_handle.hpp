// One run as the extension holds it (bind_run.cpp makes it, bind_pictures.cpp draws it): the
// prepared scene (its render settings and plot specs), the result with every row, and
// summary.json's content.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "core/simulation.hpp"
#include "services/run_service.hpp"

namespace stiction::python {

struct RunHandle {
  std::shared_ptr<services::PreparedRun> prepared;
  core::RunResult result;
  nlohmann::ordered_json summary;
  std::string status;  // "ok", "unstable", "interrupted"
};

}  // namespace stiction::python
