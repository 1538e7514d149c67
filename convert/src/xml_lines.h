// Reads an XML file with libxml2 only to know where its elements are:
// urdfdom's parser reports names but no lines, so messages find the line
// of the element that carries the name here.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace simpartner::convert {

struct UrdfLines {
  int robot = 1;                                   // the root element
  std::map<std::string, int> links;                // link name -> line
  std::map<std::string, int> joints;               // joint name -> line
  std::map<std::string, std::vector<int>> collisions;  // link name -> its <collision> lines
  std::string root_name;                           // the root element's name
  bool has_links = false;                          // any <link> under the root
  bool has_bodies = false;                         // any <body> under the root (ours)
};

// Parses text (no network, no entity expansion); throws ConvertError with
// libxml2's line and message when it is not well-formed XML.
UrdfLines ReadXmlLines(const std::string& text, const std::string& file_name);

}  // namespace simpartner::convert
