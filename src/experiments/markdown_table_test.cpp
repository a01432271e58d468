#include "experiments/markdown_table.h"

#include <gtest/gtest.h>

namespace caligo {
namespace {

TEST(MarkdownTable, WritesHeaderRuleAndRows) {
  MarkdownTable t;
  t.add_column("scene");
  t.add_column("fps", MarkdownTable::Align::kRight);
  t.add_row({"wyman-20k", "836.9"});
  t.add_row({"wyman-70k", "–"});
  EXPECT_EQ(t.str(),
            "| scene | fps |\n"
            "|---|---:|\n"
            "| wyman-20k | 836.9 |\n"
            "| wyman-70k | – |\n");
}

TEST(MarkdownTable, HeaderOnly) {
  MarkdownTable t;
  t.add_column("a");
  EXPECT_EQ(t.str(), "| a |\n|---|\n");
}

TEST(MarkdownTable, Numbers) {
  EXPECT_EQ(format_number("%.1f", 1e6 / 1195.0), "836.8");
  EXPECT_EQ(format_number("%.2fx", 2.5), "2.50x");
  EXPECT_EQ(percent(0.1234), "12.34 %");
  EXPECT_EQ(percent(0.00007, 3), "0.007 %");
}

}  // namespace
}  // namespace caligo
