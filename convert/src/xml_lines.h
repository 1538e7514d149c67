// Where the elements of an XML file are (read with the common XML layer,
// xml_document.h): urdfdom's parser reports names but no lines, so
// messages find the line of the element that carries the name here.
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

// Parses text; throws ConvertError with the first problem's line and
// message ("not well-formed XML: ..." for libxml2's) when it cannot.
UrdfLines ReadXmlLines(const std::string& text, const std::string& file_name);

}  // namespace simpartner::convert
