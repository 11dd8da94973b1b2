// A scene text with INTEGRATOR and DT placeholders, filled per run: the closed-form accuracy
// tests run one generated scene with every integrator at several steps.
#pragma once

#include <sstream>
#include <string>
#include <utility>

namespace stiction::testing {

inline std::string fill_template(std::string text, const std::string& integrator, double dt) {
  std::ostringstream d;
  d.precision(17);
  d << dt;
  for (const auto& [key, value] :
       {std::pair<std::string, std::string>{"INTEGRATOR", integrator}, {"DT", d.str()}}) {
    for (auto at = text.find(key); at != std::string::npos; at = text.find(key)) {
      text.replace(at, key.size(), value);
    }
  }
  return text;
}

}  // namespace stiction::testing
