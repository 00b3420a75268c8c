// Minimal streaming JSON writer (objects, arrays, strings, numbers, booleans, null).
#pragma once
#include <ostream>
#include <string>
#include <vector>

namespace gdr::cli {

class JsonWriter {
 public:
  explicit JsonWriter(std::ostream& out) : out_(out) {}

  void begin_object();
  void end_object();
  void begin_array();
  void end_array();
  void key(const std::string& k);  // inside an object, before each value

  void value(const std::string& v);
  void value(const char* v);
  void value(double v);  // non-finite values are written as null
  void value(long long v);
  void value(unsigned long long v);
  void value(int v) { value(static_cast<long long>(v)); }
  void value(long v) { value(static_cast<long long>(v)); }
  void value(unsigned long v) { value(static_cast<unsigned long long>(v)); }
  void value(bool v);
  void null();

  // Shorthands for key + value, and key + array of values.
  template <typename T>
  void field(const std::string& k, const T& v) {
    key(k);
    value(v);
  }
  template <typename T>
  void array_field(const std::string& k, const std::vector<T>& values) {
    key(k);
    begin_array();
    for (const T& v : values) value(v);
    end_array();
  }
  // Run phases as [{"name": ..., "seconds": ...}, ...] (any type with name and seconds).
  template <typename Phase>
  void phases_field(const std::string& k, const std::vector<Phase>& phases) {
    key(k);
    begin_array();
    for (const Phase& p : phases) {
      begin_object();
      field("name", p.name);
      field("seconds", p.seconds);
      end_object();
    }
    end_array();
  }

 private:
  void before_value();
  void write_string(const std::string& v);
  void newline();

  std::ostream& out_;
  std::vector<bool> first_;  // per open container: no element written yet
  bool after_key_ = false;
};

}  // namespace gdr::cli
