// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Benchmark suites register here (one bench_<name>.cpp each). Every suite measures its
// stages and, in the same run, a baseline of comparable size, and reports ratios: wall-clock
// numbers alone mean nothing across machines.

#ifndef POLYCUBE_IGA_BENCHMARK_REGISTRY_H
#define POLYCUBE_IGA_BENCHMARK_REGISTRY_H

#include <CGAL/Polycube_IGA/internal/json_writer.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace polycube_iga_bench {

struct Options
{
  std::string data_dir;   ///< ../shared/data
  bool quick = false;     ///< smaller sizes, for a smoke run
  int repetitions = 3;    ///< best-of-N timing
};

using Suite = std::function<void(const Options&)>;

inline std::map<std::string, Suite>& suites()
{
  static std::map<std::string, Suite> registry;
  return registry;
}

struct Register_suite
{
  Register_suite(const std::string& name, Suite s) { suites()[name] = std::move(s); }
};

/// Best of `repetitions` wall-clock runs of `f`, in seconds.
template <class F>
double best_time(int repetitions, F&& f)
{
  double best = 1e300;
  for(int r = 0; r < std::max(1, repetitions); ++r) {
    auto t0 = std::chrono::steady_clock::now();
    f();
    auto t1 = std::chrono::steady_clock::now();
    best = std::min(best, std::chrono::duration<double>(t1 - t0).count());
  }
  return best;
}

/// One result row: a case (mesh, size), named stage times, and the baseline time.
/// Prints a table line and one JSON line `{"suite":..,"case":..,"stages":{..},"ratios":{..}}`.
inline void report(const std::string& suite, const std::string& case_name,
                   const std::vector<std::pair<std::string, double>>& extra,
                   const std::vector<std::pair<std::string, double>>& stage_seconds,
                   const std::string& baseline_name, double baseline_seconds)
{
  std::printf("%-10s %-34s", suite.c_str(), case_name.c_str());
  for(const auto& [name, s] : stage_seconds)
    std::printf(" %s=%.4fs(x%.2f)", name.c_str(), s, s / baseline_seconds);
  std::printf(" | %s=%.4fs\n", baseline_name.c_str(), baseline_seconds);

  std::ostringstream os;
  CGAL::Polycube_IGA::internal::Json_writer w(os);
  w.begin_object().member("suite", suite).member("case", case_name);
  for(const auto& [k, v] : extra) w.member(k, v);
  w.key("stages").begin_object();
  for(const auto& [name, s] : stage_seconds) w.member(name, s);
  w.end_object();
  w.key("baseline").begin_object().member("name", baseline_name).member("seconds", baseline_seconds).end_object();
  w.key("ratios").begin_object();
  for(const auto& [name, s] : stage_seconds) w.member(name, s / baseline_seconds);
  w.end_object().end_object();
  std::printf("JSON %s\n", os.str().c_str());
  std::fflush(stdout);
}

} // namespace polycube_iga_bench

#endif
