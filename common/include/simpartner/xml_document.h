// The one way our programs read XML (libxml2): world and robot files,
// sequences, and the files the converter takes in. Problems go into a
// DiagnosticList with file, line and element, never to stderr.
//
// What every document gets:
//   - no network, no external DTD or entity loaded, no entity expanded;
//   - at most kMaxDocumentBytes of text;
//   - libxml2's complaints with their lines; after the first fatal error
//     only those on its line (what it says further down is guesswork about
//     a document it has already misread, say a tag mismatch at </world>
//     because it dropped a start tag);
//   - the DOCTYPE policy below;
//   - validation against a DTD the caller brings (built into the program,
//     cmake/EmbedDtds.cmake), so validation never depends on where a
//     program runs from and a file cannot bring its own.
//
// DOCTYPE policy. A file is validated against the program's own DTD, so a
// DOCTYPE can only say which one:
//   - none (every shipped file);
//   - <!DOCTYPE world> or <!DOCTYPE world []>: the root's name, nothing
//     declared;
//   - <!DOCTYPE world SYSTEM "world.dtd"> (any directory before the name):
//     the DTD the file is validated against, named, never read.
// Anything else is refused at the DOCTYPE's line: declarations inside the
// file (they would widen the DTD; entities among them) at parsing, for
// every document; at validation a DOCTYPE naming another element, a
// PUBLIC identifier, or another DTD file.
//
// libxml2 reports errors through a handler that it keeps per thread: the
// parse and the validation set ours for their duration and put back the
// one before, so documents can be read on several threads at once.
#pragma once

#include <libxml/tree.h>

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "simpartner/diagnostic.h"

namespace simpartner::xml {

// The largest document read (the model loader reads files up to the same
// size, model::kMaxModelFileBytes; the largest shipped file is ~100 KB).
inline constexpr size_t kMaxDocumentBytes = 64 * 1024 * 1024;

// A DTD built into the program.
struct Dtd {
  std::string file_name;  // as a DOCTYPE may name it: "world.dtd"
  std::string_view text;
};

// A parsed document; owns libxml2's tree, which its nodes point into.
class Document {
 public:
  // Parses text (file_name is for messages). Nothing, with diagnostics,
  // when it is too large, not well-formed, has no root element, or
  // declares things in its DOCTYPE. libxml2's errors that still leave a
  // document (rare) are in diagnostics too: a caller that reads on checks
  // diagnostics before it trusts the result.
  static std::optional<Document> Parse(std::string_view text, const std::string& file_name,
                                       DiagnosticList* diagnostics);

  // Parse, then the root must be <root_name>, then Validate.
  static std::optional<Document> Read(std::string_view text, const std::string& file_name,
                                      const char* root_name, const Dtd& dtd,
                                      DiagnosticList* diagnostics);

  // The DOCTYPE checked against dtd (the policy above), then the document
  // against dtd; false with diagnostics when either fails.
  bool Validate(const Dtd& dtd, DiagnosticList* diagnostics) const;

  const xmlNode* root() const;
  const std::string& file_name() const { return file_name_; }

 private:
  struct FreeDoc {
    void operator()(xmlDoc* doc) const;
  };
  Document(xmlDoc* doc, std::string file_name, int doctype_line);
  bool CheckDoctype(const Dtd& dtd, DiagnosticList* diagnostics) const;

  std::unique_ptr<xmlDoc, FreeDoc> doc_;
  std::string file_name_;
  int doctype_line_ = 0;  // libxml2 keeps no line for the DOCTYPE; the text has it
};

// Node helpers; each takes null and then returns nothing ("", 0, nullopt).
std::string Name(const xmlNode* node);
int Line(const xmlNode* node);
std::optional<std::string> Attribute(const xmlNode* node, const char* name);
// The first child element named name.
const xmlNode* Child(const xmlNode* parent, const char* name);
// The child elements named name (every child element when name is null),
// in document order.
std::vector<const xmlNode*> Children(const xmlNode* parent, const char* name = nullptr);
// The element's text as written, white space and line breaks included.
std::string RawText(const xmlNode* node);
// The element's text without leading and trailing blanks.
std::string Text(const xmlNode* node);

// A diagnostic at node: its line and element name.
void AddAt(DiagnosticList* diagnostics, const std::string& file_name, const xmlNode* node,
           const std::string& message);

}  // namespace simpartner::xml
