// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// `polycube_iga`: the command-line tool. Each subcommand lives in cli/<name>_command.cpp.
// Exit codes: 0 success, 2 invalid input, 3 topology not supported by the stage,
// 1 internal failure. Every failure prints one line `error: <reason>: <sentence>`.

#include "cli/command_registry.h"

#include <CGAL/Polycube_IGA/Errors.h>

#include <exception>
#include <iostream>
#include <new>

namespace {

void print_help(std::ostream& os)
{
  os << "usage: polycube_iga <command> [options]\n\ncommands:\n";
  for(const auto& [name, command] : polycube_iga_cli::command_registry())
    os << "  " << name << std::string(name.size() < 14 ? 14 - name.size() : 1, ' ')
       << command.summary << "\n";
  os << "\n'polycube_iga <command> --help' shows a command's options.\n"
        "exit codes: 0 success, 1 internal failure, 2 invalid input, 3 unsupported topology\n";
}

} // namespace

int main(int argc, char** argv)
{
  using namespace polycube_iga_cli;
  if(argc < 2) { print_help(std::cerr); return 2; }
  const std::string name = argv[1];
  if(name == "--help" || name == "-h" || name == "help") { print_help(std::cout); return 0; }
  auto it = command_registry().find(name);
  if(it == command_registry().end()) {
    std::cerr << "error: bad_arguments: unknown command '" << name << "' (see polycube_iga --help)\n";
    return 2;
  }
  Arguments args(argv + 2, argv + argc);
  for(const std::string& a : args)
    if(a == "--help" || a == "-h") { std::cout << it->second.usage; return 0; }
  try {
    return it->second.run(args);
  } catch(const CGAL::Polycube_IGA::Error& e) {
    std::cerr << "error: " << e.reason() << ": " << e.what() << "\n";
    return e.exit_code();
  } catch(const std::bad_alloc&) {
    std::cerr << "error: out_of_memory: the computation ran out of memory\n";
    return 1;
  } catch(const std::exception& e) {
    std::cerr << "error: internal_error: " << e.what() << "\n";
    return 1;
  }
}
