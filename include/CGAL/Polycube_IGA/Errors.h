// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Error types of the package. Every failure carries a machine-readable reason code
// (`non_manifold_edge`, `no_pants_decomposition`, ...) and a sentence a user understands.
// The kind of failure is the exception type, which the CLI maps to its exit code:
// invalid input -> 2, unsupported topology -> 3, anything else -> 1.

#ifndef CGAL_POLYCUBE_IGA_ERRORS_H
#define CGAL_POLYCUBE_IGA_ERRORS_H

#include <stdexcept>
#include <string>

namespace CGAL {
namespace Polycube_IGA {

/// \ingroup PkgPolycubeIGARef
/// Base class of every exception thrown by the package.
class Error : public std::runtime_error
{
public:
  Error(std::string reason, const std::string& sentence)
    : std::runtime_error(sentence), reason_(std::move(reason)) {}
  /// Machine-readable reason code, lower_case_with_underscores.
  const std::string& reason() const { return reason_; }
  /// Exit code the command-line tool uses for this kind of failure.
  virtual int exit_code() const { return 1; }

private:
  std::string reason_;
};

/// The input (file, mesh, grid, option) is malformed: exit code 2.
class Invalid_input_error : public Error
{
public:
  using Error::Error;
  int exit_code() const override { return 2; }
};

/// The input is valid, but the requested stage does not support its topology: exit code 3.
class Unsupported_topology_error : public Error
{
public:
  using Error::Error;
  int exit_code() const override { return 3; }
};

/// A computation failed although its input was valid (solver breakdown, a violated
/// internal invariant): exit code 1. These are bugs or numerical limits worth reporting.
class Internal_error : public Error
{
public:
  using Error::Error;
  int exit_code() const override { return 1; }
};

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_ERRORS_H
