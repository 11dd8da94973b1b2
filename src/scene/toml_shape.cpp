#include "scene/toml_shape.hpp"

#include <cctype>

#include "scene/toml_reader.hpp"

namespace stiction::scene {
namespace {

class Scanner {
 public:
  Scanner(const std::string& text, const std::string& origin) : text_(text), origin_(origin) {}

  void run() {
    while (i_ < text_.size()) {
      const char c = text_[i_];
      if (c == '#') {
        skip_comment();
      } else if (c == '"' || c == '\'') {
        skip_string(c);
      } else if (c == '[' || c == '{') {
        if (++depth_ > TomlShapeLimits::kMaxNesting) {
          fail("more than " + std::to_string(TomlShapeLimits::kMaxNesting) +
               " nested arrays, inline tables or header brackets");
        }
        reset_key();
        advance();
      } else if (c == ']' || c == '}') {
        if (depth_ > 0) --depth_;
        reset_key();
        advance();
      } else if (c == '.') {
        // A dot joins two parts of a key (or sits inside a number: one per number).
        if (++dots_ >= TomlShapeLimits::kMaxKeyParts) {
          fail("a dotted key of more than " + std::to_string(TomlShapeLimits::kMaxKeyParts) +
               " parts");
        }
        advance();
      } else if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '+' ||
                 c == ' ' || c == '\t') {
        advance();
      } else {
        reset_key();  // '=', ',', newline, ':' ...: a key ends here
        advance();
      }
    }
  }

 private:
  void reset_key() {
    dots_ = 0;
  }
  void advance() {
    if (text_[i_] == '\n') {
      ++line_;
      line_start_ = i_ + 1;
    }
    ++i_;
  }
  void skip_comment() {
    while (i_ < text_.size() && text_[i_] != '\n') ++i_;
  }
  // A basic or literal string, single- or multi-line; an unterminated one ends the scan
  // (toml++ reports it).
  void skip_string(char quote) {
    const bool multi = text_.compare(i_, 3, std::string(3, quote)) == 0;
    const std::size_t open = multi ? 3 : 1;
    for (std::size_t k = 0; k < open; ++k) advance();
    while (i_ < text_.size()) {
      const char c = text_[i_];
      if (c == '\\' && quote == '"') {
        advance();
        if (i_ < text_.size()) advance();
        continue;
      }
      if (c == quote && (!multi || text_.compare(i_, 3, std::string(3, quote)) == 0)) {
        for (std::size_t k = 0; k < open; ++k) advance();
        return;
      }
      if (c == '\n' && !multi) return;
      advance();
    }
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(origin_ + ":" + std::to_string(line_) + ":" +
                     std::to_string(i_ - line_start_ + 1) + ": error: " + what +
                     " (a scene needs a few; the reader stops at this bound, docs/limits.md)");
  }

  const std::string& text_;
  const std::string& origin_;
  std::size_t i_ = 0;
  long line_ = 1;
  std::size_t line_start_ = 0;
  int depth_ = 0;
  int dots_ = 0;
};

}  // namespace

void check_toml_shape(const std::string& text, const std::string& origin) {
  Scanner(text, origin).run();
}

}  // namespace stiction::scene
