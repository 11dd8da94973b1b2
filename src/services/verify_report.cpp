#include "services/verify_report.hpp"

#include <sstream>

#include "io/atomic_file.hpp"
#include "text/xml_escape.hpp"

namespace stiction::services {
namespace {

// Markdown table cells: a '|' would end the cell.
std::string escape_cell(const std::string& s) {
  std::string out;
  for (char c : s)
    out += c == '|' ? std::string("\\|") : c == '\n' ? std::string(" ") : std::string(1, c);
  return out;
}

int count(const SceneVerdict& v, ItemStatus s) {
  int n = 0;
  for (const VerifyItem& i : v.items) n += i.status == s;
  return n;
}

std::string verdict_word(const SceneVerdict& v) {
  if (!v.error.empty()) return "ERROR";
  return v.failed() ? "FAILED" : "passed";
}

}  // namespace

std::string verify_markdown(const std::vector<SceneVerdict>& verdicts, const std::string& golden) {
  std::ostringstream md;
  int failed = 0;
  for (const auto& v : verdicts) failed += v.failed();
  md << "# stiction verify\n\n";
  md << "Golden set: `" << golden << "`. " << verdicts.size() << " scene(s), " << failed
     << " failed.\n\n";
  md << "| scene | verdict | items | mismatches |\n|---|---|---|---|\n";
  for (const auto& v : verdicts) {
    md << "| " << escape_cell(v.scene) << " | " << verdict_word(v) << " | " << v.items.size()
       << " | " << count(v, ItemStatus::mismatch) << " |\n";
  }
  for (const auto& v : verdicts) {
    md << "\n## " << v.scene << ": " << verdict_word(v) << "\n\n";
    if (!v.error.empty()) md << "Error: " << v.error << "\n\n";
    md << "| item | what | status | detail |\n|---|---|---|---|\n";
    for (const VerifyItem& i : v.items) {
      md << "| " << i.name << " | " << escape_cell(i.what) << " | " << status_name(i.status)
         << " | " << escape_cell(i.detail) << " |\n";
    }
    for (const VerifyItem& i : v.items) {
      if (i.status != ItemStatus::mismatch) continue;
      if (!i.actual.empty() || !i.differences.empty()) md << "\n### " << i.name << "\n\n";
      if (!i.actual.empty()) {
        md << "actual `" << i.actual << "`";
        if (!i.golden.empty()) md << ", golden `" << i.golden << "`, diff `" << i.diff << "`";
        md << "\n\n";
        if (!i.diff.empty()) {
          md << "| actual | golden | diff |\n|---|---|---|\n| ![actual](" << i.actual
             << ") | ![golden](" << i.golden << ") | ![diff](" << i.diff << ") |\n";
        }
      }
      for (const std::string& d : i.differences) md << "- " << d << "\n";
    }
  }
  return md.str();
}

std::string verify_html(const std::vector<SceneVerdict>& verdicts, const std::string& golden) {
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
    << "<title>stiction verify</title>\n<style>\n"
    << "body{font-family:sans-serif;margin:1.5em}table{border-collapse:collapse}"
    << "td,th{border:1px solid #ccc;padding:3px 8px;text-align:left;vertical-align:top}"
    << ".MISMATCH,.FAILED,.ERROR{color:#b00;font-weight:bold}.match,.passed{color:#070}"
    << "figure{display:inline-block;margin:0 8px 8px 0}img{max-width:32vw;border:1px solid #999}"
    << "</style>\n</head>\n<body>\n<h1>stiction verify</h1>\n<p>Golden set: <code>"
    << text::xml_escaped(golden) << "</code></p>\n";
  h << "<table>\n<tr><th>scene</th><th>verdict</th><th>items</th><th>mismatches</th></tr>\n";
  for (const auto& v : verdicts) {
    h << "<tr><td><a href=\"#" << text::xml_escaped(v.scene) << "\">" << text::xml_escaped(v.scene)
      << "</a></td><td class=\"" << verdict_word(v) << "\">" << verdict_word(v) << "</td><td>"
      << v.items.size() << "</td><td>" << count(v, ItemStatus::mismatch) << "</td></tr>\n";
  }
  h << "</table>\n";
  for (const auto& v : verdicts) {
    h << "<h2 id=\"" << text::xml_escaped(v.scene) << "\">" << text::xml_escaped(v.scene)
      << ": <span class=\"" << verdict_word(v) << "\">" << verdict_word(v) << "</span></h2>\n";
    if (!v.error.empty()) h << "<p class=\"ERROR\">" << text::xml_escaped(v.error) << "</p>\n";
    h << "<table>\n<tr><th>item</th><th>what</th><th>status</th><th>detail</th></tr>\n";
    for (const VerifyItem& i : v.items) {
      h << "<tr><td>" << text::xml_escaped(i.name) << "</td><td>" << text::xml_escaped(i.what)
        << "</td><td class=\"" << status_name(i.status) << "\">" << status_name(i.status)
        << "</td><td>" << text::xml_escaped(i.detail) << "</td></tr>\n";
    }
    h << "</table>\n";
    for (const VerifyItem& i : v.items) {
      if (i.status != ItemStatus::mismatch) continue;
      h << "<h3>" << text::xml_escaped(i.name) << ": " << text::xml_escaped(i.what)
        << "</h3>\n<div>\n";
      const auto image = [&](const std::string& file, const char* caption) {
        if (file.empty()) return;
        h << "<figure><img src=\"" << text::xml_escaped(file) << "\" alt=\"" << caption
          << "\"><figcaption>" << caption << " <code>" << text::xml_escaped(file)
          << "</code></figcaption></figure>\n";
      };
      image(i.actual, "actual");
      image(i.golden, "golden");
      image(i.diff, "diff (red: beyond tolerance, yellow: within)");
      h << "</div>\n";
      if (!i.differences.empty()) {
        h << "<ul>\n";
        for (const std::string& d : i.differences)
          h << "<li><code>" << text::xml_escaped(d) << "</code></li>\n";
        h << "</ul>\n";
      }
    }
  }
  h << "</body>\n</html>\n";
  return h.str();
}

std::string verify_junit(const std::vector<SceneVerdict>& verdicts) {
  std::ostringstream x;
  int tests = 0, failures = 0, errors = 0;
  for (const auto& v : verdicts) {
    tests += static_cast<int>(v.items.size()) + (v.error.empty() ? 0 : 1);
    failures += count(v, ItemStatus::mismatch);
    errors += v.error.empty() ? 0 : 1;
  }
  x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  x << "<testsuites name=\"stiction verify\" tests=\"" << tests << "\" failures=\"" << failures
    << "\" errors=\"" << errors << "\">\n";
  for (const auto& v : verdicts) {
    const int f = count(v, ItemStatus::mismatch);
    x << "  <testsuite name=\"" << text::xml_escaped(v.scene) << "\" tests=\""
      << v.items.size() + (v.error.empty() ? 0 : 1) << "\" failures=\"" << f << "\" errors=\""
      << (v.error.empty() ? 0 : 1) << "\">\n";
    for (const VerifyItem& i : v.items) {
      x << "    <testcase classname=\"stiction.verify." << text::xml_escaped(v.scene)
        << "\" name=\"" << text::xml_escaped(i.name + ": " + i.what) << "\"";
      if (i.status != ItemStatus::mismatch) {
        x << "/>\n";
        continue;
      }
      x << ">\n      <failure type=\"mismatch\" message=\"" << text::xml_escaped(i.detail) << "\">";
      std::string body = i.detail;
      if (!i.actual.empty()) body += "\nactual: " + i.actual;
      if (!i.golden.empty()) body += "\ngolden: " + i.golden;
      if (!i.diff.empty()) body += "\ndiff: " + i.diff;
      for (const std::string& d : i.differences) body += "\n" + d;
      x << text::xml_escaped(body) << "</failure>\n    </testcase>\n";
    }
    if (!v.error.empty()) {
      x << "    <testcase classname=\"stiction.verify." << text::xml_escaped(v.scene)
        << "\" name=\"run\">\n      <error message=\"" << text::xml_escaped(v.error)
        << "\"/>\n    </testcase>\n";
    }
    x << "  </testsuite>\n";
  }
  x << "</testsuites>\n";
  return x.str();
}

void write_verify_reports(const std::vector<SceneVerdict>& verdicts, const std::string& golden,
                          const std::filesystem::path& dir) {
  io::write_file_atomically(dir / "report.md", verify_markdown(verdicts, golden));
  io::write_file_atomically(dir / "report.html", verify_html(verdicts, golden));
  io::write_file_atomically(dir / "junit.xml", verify_junit(verdicts));
}

}  // namespace stiction::services
