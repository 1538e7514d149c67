#include "xml_lines.h"

#include <libxml/parser.h>
#include <libxml/tree.h>

#include <algorithm>
#include <memory>

#include "simpartner/convert/urdf_import.h"

namespace simpartner::convert {
namespace {

std::string Attribute(const xmlNode* node, const char* name) {
  xmlChar* value = xmlGetProp(node, reinterpret_cast<const xmlChar*>(name));
  if (value == nullptr) return "";
  std::string text(reinterpret_cast<const char*>(value));
  xmlFree(value);
  return text;
}

bool Named(const xmlNode* node, const char* name) {
  return node->type == XML_ELEMENT_NODE &&
         xmlStrcmp(node->name, reinterpret_cast<const xmlChar*>(name)) == 0;
}

// The first error libxml2 raises: what follows it is about a document it
// has already misread (an unclosed tag shows up at the end of the file).
struct FirstError {
  int line = 0;
  std::string message;
};

void KeepFirstError(void* data, xmlErrorPtr error) {
  auto* context = static_cast<xmlParserCtxt*>(data);
  auto* first = static_cast<FirstError*>(context->_private);
  if (first == nullptr || error == nullptr || error->level == XML_ERR_WARNING) return;
  if (!first->message.empty()) return;
  first->line = error->line;
  first->message = error->message != nullptr ? error->message : "not well-formed XML";
  while (!first->message.empty() &&
         (first->message.back() == '\n' || first->message.back() == ' '))
    first->message.pop_back();
  std::replace(first->message.begin(), first->message.end(), '\n', ' ');
}

}  // namespace

UrdfLines ReadXmlLines(const std::string& text, const std::string& file_name) {
  std::unique_ptr<xmlParserCtxt, decltype(&xmlFreeParserCtxt)> context(xmlNewParserCtxt(),
                                                                        &xmlFreeParserCtxt);
  if (!context) {
    DiagnosticList diagnostics;
    diagnostics.Add(file_name, 0, "", "cannot start the XML parser (out of memory)");
    throw ConvertError(diagnostics);
  }
  // No network, no external entities, and libxml2 prints nothing: the
  // first error comes back through the context's own handler (libxml2
  // passes the context as the handler's data).
  FirstError first;
  context->_private = &first;
  context->sax->serror = &KeepFirstError;
  const int flags = XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING;
  std::unique_ptr<xmlDoc, decltype(&xmlFreeDoc)> doc(
      xmlCtxtReadMemory(context.get(), text.data(), static_cast<int>(text.size()),
                        file_name.c_str(), nullptr, flags),
      &xmlFreeDoc);
  if (!doc) {
    DiagnosticList diagnostics;
    diagnostics.Add(file_name, first.line, "",
                    "not well-formed XML: " +
                        (first.message.empty() ? std::string("cannot parse") : first.message));
    throw ConvertError(diagnostics);
  }
  UrdfLines lines;
  const xmlNode* root = xmlDocGetRootElement(doc.get());
  if (root == nullptr) return lines;
  lines.robot = static_cast<int>(xmlGetLineNo(root));
  lines.root_name = reinterpret_cast<const char*>(root->name);
  for (const xmlNode* child = root->children; child != nullptr; child = child->next) {
    const int line = static_cast<int>(xmlGetLineNo(child));
    if (Named(child, "link")) {
      lines.has_links = true;
      const std::string name = Attribute(child, "name");
      lines.links.emplace(name, line);
      for (const xmlNode* part = child->children; part != nullptr; part = part->next) {
        if (Named(part, "collision"))
          lines.collisions[name].push_back(static_cast<int>(xmlGetLineNo(part)));
      }
    } else if (Named(child, "joint")) {
      lines.joints.emplace(Attribute(child, "name"), line);
    } else if (Named(child, "body")) {
      lines.has_bodies = true;
    }
  }
  return lines;
}

}  // namespace simpartner::convert
