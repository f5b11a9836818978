// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// polycube_iga_benchmark [--quick] [--repetitions N] [--data DIR] [suite ...]
// Runs the registered suites (all by default) and prints a table plus JSON lines.

#include "benchmark_registry.h"

#include <cstdlib>
#include <cstring>

int main(int argc, char** argv)
{
  polycube_iga_bench::Options opt;
  opt.data_dir = POLYCUBE_IGA_SHARED_DATA_DIR;
  std::vector<std::string> selected;
  for(int i = 1; i < argc; ++i) {
    if(!std::strcmp(argv[i], "--quick")) opt.quick = true;
    else if(!std::strcmp(argv[i], "--repetitions") && i + 1 < argc) opt.repetitions = std::atoi(argv[++i]);
    else if(!std::strcmp(argv[i], "--data") && i + 1 < argc) opt.data_dir = argv[++i];
    else if(argv[i][0] == '-') {
      std::cerr << "usage: polycube_iga_benchmark [--quick] [--repetitions N] [--data DIR] [suite ...]\nsuites:";
      for(const auto& s : polycube_iga_bench::suites()) std::cerr << " " << s.first;
      std::cerr << "\n";
      return 2;
    }
    else selected.push_back(argv[i]);
  }
  for(const auto& [name, suite] : polycube_iga_bench::suites())
    if(selected.empty() || std::find(selected.begin(), selected.end(), name) != selected.end())
      suite(opt);
  return 0;
}
