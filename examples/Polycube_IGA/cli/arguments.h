// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Small argument parser shared by the subcommands: positional arguments, flags and
// `--option value` pairs. Unknown or malformed options are invalid input (exit code 2).

#ifndef POLYCUBE_IGA_CLI_ARGUMENTS_H
#define POLYCUBE_IGA_CLI_ARGUMENTS_H

#include <CGAL/Polycube_IGA/Errors.h>

#include <cstdlib>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace polycube_iga_cli {

class Parsed_arguments
{
public:
  /// `flags`: options without value; `options`: options followed by one value.
  Parsed_arguments(const std::vector<std::string>& args,
                   const std::set<std::string>& flags,
                   const std::set<std::string>& options)
  {
    for(std::size_t i = 0; i < args.size(); ++i) {
      const std::string& a = args[i];
      if(a.size() > 1 && a[0] == '-' && !is_number(a)) {
        if(flags.count(a)) { flags_.insert(a); continue; }
        if(options.count(a)) {
          if(i + 1 >= args.size())
            throw CGAL::Polycube_IGA::Invalid_input_error("bad_arguments", "option " + a + " needs a value");
          values_[a] = args[++i];
          continue;
        }
        throw CGAL::Polycube_IGA::Invalid_input_error("bad_arguments", "unknown option " + a);
      }
      positional_.push_back(a);
    }
  }

  bool has(const std::string& flag) const { return flags_.count(flag) || values_.count(flag); }
  const std::vector<std::string>& positional() const { return positional_; }

  std::string get(const std::string& option, const std::string& fallback = "") const
  {
    auto it = values_.find(option);
    return it == values_.end() ? fallback : it->second;
  }

  long get_integer(const std::string& option, long fallback, long lo, long hi) const
  {
    auto it = values_.find(option);
    if(it == values_.end()) return fallback;
    char* end = nullptr;
    long v = std::strtol(it->second.c_str(), &end, 10);
    if(end == it->second.c_str() || *end != '\0' || v < lo || v > hi)
      throw CGAL::Polycube_IGA::Invalid_input_error("bad_arguments",
        option + " expects an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
        "], got '" + it->second + "'");
    return v;
  }

  double get_real(const std::string& option, double fallback) const
  {
    auto it = values_.find(option);
    if(it == values_.end()) return fallback;
    char* end = nullptr;
    double v = std::strtod(it->second.c_str(), &end);
    if(end == it->second.c_str() || *end != '\0' || !(v == v))
      throw CGAL::Polycube_IGA::Invalid_input_error("bad_arguments",
        option + " expects a number, got '" + it->second + "'");
    return v;
  }

  /// Exactly `n` positional arguments, else invalid input naming `what`.
  void expect_positional(std::size_t n, const std::string& what) const
  {
    if(positional_.size() != n)
      throw CGAL::Polycube_IGA::Invalid_input_error("bad_arguments", "expected " + what);
  }

private:
  static bool is_number(const std::string& s)
  {
    char* end = nullptr;
    std::strtod(s.c_str(), &end);
    return end != s.c_str() && *end == '\0';
  }

  std::vector<std::string> positional_;
  std::set<std::string> flags_;
  std::map<std::string, std::string> values_;
};

} // namespace polycube_iga_cli

#endif
