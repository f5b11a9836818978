// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Small readers of the VTK XML files the package writes, for the tests (no VTK needed): the
// file's text, a tag-balance check, attributes and the text or integers of a DataArray.

#ifndef POLYCUBE_IGA_TEST_VTU_TEXT_H
#define POLYCUBE_IGA_TEST_VTU_TEXT_H

#include <CGAL/Polycube_IGA/internal/number_text.h>

#include <fstream>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <vector>

namespace test_support {

inline std::string file_text(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline bool exists(const std::string& path)
{
  struct stat st;
  return ::stat(path.c_str(), &st) == 0;
}

/// Every start tag has its end tag, properly nested; one root element `VTKFile`.
inline bool xml_tags_balance(const std::string& xml)
{
  std::vector<std::string> open;
  std::size_t roots = 0;
  for(std::size_t at = xml.find('<'); at != std::string::npos; at = xml.find('<', at + 1)) {
    const std::size_t end = xml.find('>', at);
    if(end == std::string::npos) return false;
    const std::string tag = xml.substr(at + 1, end - at - 1);
    if(tag.empty()) return false;
    if(tag[0] == '?') continue; // declaration
    if(tag[0] == '/') {
      if(open.empty() || open.back() != tag.substr(1)) return false;
      open.pop_back();
      continue;
    }
    const std::string name = tag.substr(0, tag.find_first_of(" \n/"));
    if(open.empty()) {
      ++roots;
      if(name != "VTKFile") return false;
    }
    if(tag.back() != '/') open.push_back(name);
  }
  return open.empty() && roots == 1;
}

inline std::string attribute(const std::string& xml, const std::string& element, const std::string& name)
{
  const std::size_t at = xml.find("<" + element + " ");
  if(at == std::string::npos) return "";
  const std::size_t close = xml.find('>', at);
  const std::size_t a = xml.find(" " + name + "=\"", at);
  if(a == std::string::npos || a > close) return "";
  const std::size_t begin = a + name.size() + 3;
  return xml.substr(begin, xml.find('"', begin) - begin);
}

/// Text of the DataArray named `name` (or of the first DataArray after `after`).
inline std::string data_array(const std::string& xml, const std::string& name, const std::string& after = "")
{
  std::size_t at = after.empty() ? xml.find("Name=\"" + name + "\"") : xml.find("<DataArray", xml.find(after));
  if(at == std::string::npos) return "";
  const std::size_t begin = xml.find('>', at) + 1;
  return xml.substr(begin, xml.find("</DataArray>", begin) - begin);
}

inline std::vector<long> integers(const std::string& xml, const std::string& name)
{
  return CGAL::Polycube_IGA::internal::parse_integers(data_array(xml, name), name);
}

} // namespace test_support

#endif
