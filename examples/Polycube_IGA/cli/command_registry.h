// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Subcommands of the `polycube_iga` tool register themselves here, one source file each,
// so that adding a stage never edits the dispatcher.

#ifndef POLYCUBE_IGA_CLI_COMMAND_REGISTRY_H
#define POLYCUBE_IGA_CLI_COMMAND_REGISTRY_H

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace polycube_iga_cli {

using Arguments = std::vector<std::string>;

struct Command
{
  std::string summary; ///< one line for `polycube_iga --help`
  std::string usage;   ///< full usage text for `polycube_iga CMD --help`
  std::function<int(const Arguments&)> run; ///< returns the exit code; may throw Polycube_IGA errors
};

inline std::map<std::string, Command>& command_registry()
{
  static std::map<std::string, Command> registry;
  return registry;
}

struct Register_command
{
  Register_command(const std::string& name, Command command)
  {
    command_registry()[name] = std::move(command);
  }
};

} // namespace polycube_iga_cli

#endif
