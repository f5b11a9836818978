// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Atomic output: write to a temporary file beside the target, then rename, so that a
// failure never leaves a half-written file where the user expects a result.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_ATOMIC_FILE_H
#define CGAL_POLYCUBE_IGA_INTERNAL_ATOMIC_FILE_H

#include <CGAL/Polycube_IGA/Errors.h>

#include <cstdio>
#include <fstream>
#include <functional>
#include <string>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

/// Calls `writer(stream)` on a temporary file and renames it to `path` on success.
/// Any exception from `writer`, or a stream failure, removes the temporary and rethrows.
inline void write_file_atomically(const std::string& path,
                                  const std::function<void(std::ostream&)>& writer,
                                  bool binary = false)
{
  const std::string tmp = path + ".tmp-polycube-iga";
  {
    std::ofstream out(tmp, binary ? std::ios::binary : std::ios::out);
    if(!out)
      throw Invalid_input_error("unwritable_output", "cannot open '" + path + "' for writing");
    out.precision(17);
    try { writer(out); }
    catch(...) { out.close(); std::remove(tmp.c_str()); throw; }
    out.flush();
    if(!out) {
      out.close(); std::remove(tmp.c_str());
      throw Internal_error("write_failed", "writing '" + path + "' failed (disk full?)");
    }
  }
  if(std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw Internal_error("write_failed", "cannot move the output into place at '" + path + "'");
  }
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif
