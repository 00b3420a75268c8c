// Plain-text summary tables and number formatting for the CLI.
#pragma once
#include <cstddef>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace gdr::cli {

// Rows of cells printed with aligned columns; the first column is left-aligned, the others
// right-aligned (numbers) or left-aligned (text). A row with one cell is a section heading.
class Table {
 public:
  enum class Align { Right, Left };
  explicit Table(Align values = Align::Right) : align_(values) {}
  void row(std::vector<std::string> cells) { rows_.push_back(std::move(cells)); }
  void print(std::ostream& out, const std::string& indent = "  ") const;

 private:
  Align align_;
  std::vector<std::vector<std::string>> rows_;
};

std::string with_commas(long long n);           // 1234567 -> "1,234,567"
std::string fixed(double v, int decimals);      // "%.*f"
std::string seconds(double s);                  // "0.123 s", "12.3 s"
std::string bytes(std::size_t n);               // "12.3 MiB"

}  // namespace gdr::cli
