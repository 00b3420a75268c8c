#include "json_writer.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace gdr::cli {

void JsonWriter::newline() {
  out_ << '\n' << std::string(2 * first_.size(), ' ');
}

void JsonWriter::before_value() {
  if (after_key_) {
    after_key_ = false;
    return;
  }
  if (!first_.empty()) {
    if (!first_.back()) out_ << ',';
    first_.back() = false;
    newline();
  }
}

void JsonWriter::begin_object() {
  before_value();
  out_ << '{';
  first_.push_back(true);
}

void JsonWriter::end_object() {
  const bool empty = first_.back();
  first_.pop_back();
  if (!empty) newline();
  out_ << '}';
  if (first_.empty()) out_ << '\n';
}

void JsonWriter::begin_array() {
  before_value();
  out_ << '[';
  first_.push_back(true);
}

void JsonWriter::end_array() {
  const bool empty = first_.back();
  first_.pop_back();
  if (!empty) newline();
  out_ << ']';
}

void JsonWriter::key(const std::string& k) {
  before_value();
  write_string(k);
  out_ << ": ";
  after_key_ = true;
}

void JsonWriter::value(const std::string& v) {
  before_value();
  write_string(v);
}

void JsonWriter::write_string(const std::string& v) {
  out_ << '"';
  for (const char ch : v) {
    const auto c = static_cast<unsigned char>(ch);
    switch (c) {
      case '"': out_ << "\\\""; break;
      case '\\': out_ << "\\\\"; break;
      case '\n': out_ << "\\n"; break;
      case '\t': out_ << "\\t"; break;
      case '\r': out_ << "\\r"; break;
      default:
        if (c < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out_ << buf;
        } else {
          out_ << ch;
        }
    }
  }
  out_ << '"';
}

void JsonWriter::value(const char* v) { value(std::string(v)); }

void JsonWriter::value(double v) {
  if (!std::isfinite(v)) {
    null();
    return;
  }
  before_value();
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.15g", v);  // short when it reads back exactly
  if (std::strtod(buf, nullptr) != v) std::snprintf(buf, sizeof buf, "%.17g", v);
  out_ << buf;
}

void JsonWriter::value(long long v) {
  before_value();
  out_ << v;
}

void JsonWriter::value(unsigned long long v) {
  before_value();
  out_ << v;
}

void JsonWriter::value(bool v) {
  before_value();
  out_ << (v ? "true" : "false");
}

void JsonWriter::null() {
  before_value();
  out_ << "null";
}

}  // namespace gdr::cli
