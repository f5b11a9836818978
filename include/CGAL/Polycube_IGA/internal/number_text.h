// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Text form of numbers for the spline file formats: doubles with 17 significant digits
// (%.17g reads back bit for bit through strtod) and strict parsing of whitespace-separated
// lists, which reports malformed text as Invalid_input_error `unreadable`.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_NUMBER_TEXT_H
#define CGAL_POLYCUBE_IGA_INTERNAL_NUMBER_TEXT_H

#include <CGAL/Polycube_IGA/Errors.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <ostream>
#include <string>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

inline void write_double(std::ostream& os, double x)
{
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.17g", x);
  os << buf;
}

inline std::vector<double> parse_doubles(const std::string& text, const std::string& what)
{
  std::vector<double> r;
  const char* s = text.c_str();
  for(;;) {
    while(*s == ' ' || *s == '\n' || *s == '\t' || *s == '\r') ++s;
    if(!*s) break;
    char* end = nullptr;
    const double x = std::strtod(s, &end);
    if(end == s) throw Invalid_input_error("unreadable", what + ": '" + std::string(s, std::min<std::size_t>(20, std::char_traits<char>::length(s))) + "' is not a number");
    r.push_back(x);
    s = end;
  }
  return r;
}

inline std::vector<long> parse_integers(const std::string& text, const std::string& what)
{
  std::vector<long> r;
  for(double x : parse_doubles(text, what)) {
    if(x != double(long(x))) throw Invalid_input_error("unreadable", what + ": expected integers");
    r.push_back(long(x));
  }
  return r;
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif
