// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// A minimal streaming JSON writer shared by every report the package prints. Doubles are
// written with 17 significant digits (round-trip exact, hence deterministic output);
// NaN and infinities become null, since JSON has no such numbers.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_JSON_WRITER_H
#define CGAL_POLYCUBE_IGA_INTERNAL_JSON_WRITER_H

#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

class Json_writer
{
public:
  explicit Json_writer(std::ostream& os) : os_(os) {}

  Json_writer& begin_object() { value_prefix(); os_ << '{'; first_.push_back(true); return *this; }
  Json_writer& end_object() { os_ << '}'; first_.pop_back(); return *this; }
  Json_writer& begin_array() { value_prefix(); os_ << '['; first_.push_back(true); return *this; }
  Json_writer& end_array() { os_ << ']'; first_.pop_back(); return *this; }

  /// Writes the key of the next member of the current object.
  Json_writer& key(const std::string& k)
  {
    separator();
    write_string(k);
    os_ << ':';
    after_key_ = true;
    return *this;
  }

  Json_writer& value(const std::string& s) { value_prefix(); write_string(s); return *this; }
  Json_writer& value(const char* s) { return value(std::string(s)); }
  Json_writer& value(bool b) { value_prefix(); os_ << (b ? "true" : "false"); return *this; }
  Json_writer& value(int i) { value_prefix(); os_ << i; return *this; }
  Json_writer& value(long i) { value_prefix(); os_ << i; return *this; }
  Json_writer& value(long long i) { value_prefix(); os_ << i; return *this; }
  Json_writer& value(unsigned i) { value_prefix(); os_ << i; return *this; }
  Json_writer& value(unsigned long i) { value_prefix(); os_ << i; return *this; }
  Json_writer& value(unsigned long long i) { value_prefix(); os_ << i; return *this; }
  Json_writer& value(double d)
  {
    value_prefix();
    if(!std::isfinite(d)) { os_ << "null"; return *this; }
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.17g", d);
    os_ << buf;
    return *this;
  }
  Json_writer& null() { value_prefix(); os_ << "null"; return *this; }

  template <class T>
  Json_writer& member(const std::string& k, const T& v) { key(k); return value(v); }

  template <class T>
  Json_writer& array(const std::vector<T>& values)
  {
    begin_array();
    for(const T& v : values) value(v);
    return end_array();
  }

private:
  void separator()
  {
    if(first_.empty()) return;
    if(!first_.back()) os_ << ',';
    first_.back() = false;
  }
  void value_prefix()
  {
    if(after_key_) { after_key_ = false; return; }
    separator();
  }
  void write_string(const std::string& s)
  {
    os_ << '"';
    for(char c : s) {
      switch(c) {
        case '"': os_ << "\\\""; break;
        case '\\': os_ << "\\\\"; break;
        case '\n': os_ << "\\n"; break;
        case '\t': os_ << "\\t"; break;
        case '\r': os_ << "\\r"; break;
        default:
          if(static_cast<unsigned char>(c) < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof(buf), "\\u%04x", static_cast<unsigned char>(c));
            os_ << buf;
          } else {
            os_ << c;
          }
      }
    }
    os_ << '"';
  }

  std::ostream& os_;
  std::vector<bool> first_;
  bool after_key_ = false;
};

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif
