// A GitHub-flavoured markdown table: a header row, the rule under it (which also sets each
// column's alignment), then rows of cells. The experiments write their reports with it.
#pragma once

#include <string>
#include <vector>

namespace caligo {

class MarkdownTable {
 public:
  // kDefault: "---" (the viewer's default, left); kRight: "---:" (numbers).
  enum class Align { kDefault, kRight };

  void add_column(std::string header, Align align = Align::kDefault);
  // Cells are written as given, one per column (no escaping of '|').
  void add_row(std::vector<std::string> cells);

  // "| a | b |\n|---|---:|\n| 1 | 2 |\n".
  std::string str() const;

 private:
  std::vector<std::string> headers_;
  std::vector<Align> aligns_;
  std::vector<std::vector<std::string>> rows_;
};

// One value through a printf format with one double, e.g. format_number("%.1f", fps).
std::string format_number(const char* format, double value);
// A fraction in percent with `decimals` places: percent(0.1234) is "12.34 %".
std::string percent(double fraction, int decimals = 2);

}  // namespace caligo
