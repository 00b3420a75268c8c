// One flat JSON object on one line: the contract between the baseline programs and gdr_bench.
#pragma once
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

namespace gdr_bench {

class JsonLine {
 public:
  JsonLine& add(const char* key, const std::string& value) {
    std::string escaped;
    for (char c : value) {
      if (c == '"' || c == '\\') escaped += '\\';
      escaped += (c == '\n' || c == '\r') ? ' ' : c;
    }
    return raw(key, "\"" + escaped + "\"");
  }
  JsonLine& add(const char* key, const char* value) { return add(key, std::string(value)); }
  JsonLine& add(const char* key, double value) {
    if (!std::isfinite(value)) return raw(key, "null");
    std::ostringstream s;
    s.precision(10);
    s << value;
    return raw(key, s.str());
  }
  JsonLine& add(const char* key, long long value) { return raw(key, std::to_string(value)); }
  JsonLine& add(const char* key, std::size_t value) { return raw(key, std::to_string(value)); }
  JsonLine& add(const char* key, int value) { return raw(key, std::to_string(value)); }

  void print() const {
    std::printf("{%s}\n", body_.c_str());
    std::fflush(stdout);
  }

 private:
  JsonLine& raw(const char* key, const std::string& value) {
    if (!body_.empty()) body_ += ", ";
    body_ += "\"" + std::string(key) + "\": " + value;
    return *this;
  }
  std::string body_;
};

}  // namespace gdr_bench
