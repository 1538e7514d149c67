#include "xml_lines.h"

#include "simpartner/convert/urdf_import.h"
#include "simpartner/xml_document.h"

namespace simpartner::convert {
namespace {

// The one problem a file that does not parse is reported with: the first.
// libxml2's own complaints (they name no element) say the file is not
// well-formed; the layer's refusals (DOCTYPE, size) say what they are.
ConvertError NotReadable(const DiagnosticList& problems, const std::string& file_name) {
  Diagnostic first = problems.empty() ? Diagnostic{file_name, 0, "", "cannot parse"}
                                      : problems.items().front();
  if (first.element.empty() && first.line > 0) first.message = "not well-formed XML: " + first.message;
  DiagnosticList diagnostics;
  diagnostics.Add(first);
  return ConvertError(diagnostics);
}

}  // namespace

UrdfLines ReadXmlLines(const std::string& text, const std::string& file_name) {
  DiagnosticList problems;
  const std::optional<xml::Document> doc = xml::Document::Parse(text, file_name, &problems);
  if (!doc) throw NotReadable(problems, file_name);
  UrdfLines lines;
  const xmlNode* root = doc->root();
  lines.robot = xml::Line(root);
  lines.root_name = xml::Name(root);
  for (const xmlNode* child : xml::Children(root)) {
    const std::string kind = xml::Name(child);
    if (kind == "link") {
      lines.has_links = true;
      const std::string name = xml::Attribute(child, "name").value_or("");
      lines.links.emplace(name, xml::Line(child));
      for (const xmlNode* collision : xml::Children(child, "collision"))
        lines.collisions[name].push_back(xml::Line(collision));
    } else if (kind == "joint") {
      lines.joints.emplace(xml::Attribute(child, "name").value_or(""), xml::Line(child));
    } else if (kind == "body") {
      lines.has_bodies = true;
    }
  }
  return lines;
}

}  // namespace simpartner::convert
