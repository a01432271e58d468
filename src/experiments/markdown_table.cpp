#include "experiments/markdown_table.h"

#include <cstdio>
#include <utility>

namespace caligo {

namespace {

// "| a | b |": appending piecewise (GCC 12 warns falsely on chains of operator+).
void append_row(std::string& out, const std::vector<std::string>& cells) {
  out += '|';
  for (const std::string& c : cells) {
    out += ' ';
    out += c;
    out += " |";
  }
  out += '\n';
}

}  // namespace

void MarkdownTable::add_column(std::string header, Align align) {
  headers_.push_back(std::move(header));
  aligns_.push_back(align);
}

void MarkdownTable::add_row(std::vector<std::string> cells) { rows_.push_back(std::move(cells)); }

std::string MarkdownTable::str() const {
  std::string out;
  append_row(out, headers_);
  out += '|';
  for (const Align a : aligns_) out += a == Align::kRight ? "---:|" : "---|";
  out += '\n';
  for (const auto& row : rows_) append_row(out, row);
  return out;
}

std::string format_number(const char* format, double value) {
  char s[64];
  std::snprintf(s, sizeof s, format, value);
  return s;
}

std::string percent(double fraction, int decimals) {
  char s[64];
  std::snprintf(s, sizeof s, "%.*f %%", decimals, fraction * 100.0);
  return s;
}

}  // namespace caligo
