// The reports of `stiction verify`, written to the report directory: report.md (for people
// and CI summaries), report.html (actual, golden and diff images side by side) and
// junit.xml (one testsuite per scene, one testcase per frame, figure and number set), which
// CI systems display. None of them holds a time or a machine name: the same verdicts give the
// same bytes.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "services/verify_scene.hpp"

namespace stiction::services {

std::string verify_markdown(const std::vector<SceneVerdict>& verdicts, const std::string& golden);
std::string verify_html(const std::vector<SceneVerdict>& verdicts, const std::string& golden);
std::string verify_junit(const std::vector<SceneVerdict>& verdicts);

// Writes the three files into `dir` (atomically).
void write_verify_reports(const std::vector<SceneVerdict>& verdicts, const std::string& golden,
                          const std::filesystem::path& dir);

}  // namespace stiction::services
