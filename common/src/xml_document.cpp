#include "simpartner/xml_document.h"

#include <libxml/globals.h>
#include <libxml/parser.h>
#include <libxml/valid.h>
#include <libxml/xmlerror.h>

#include <algorithm>
#include <climits>
#include <filesystem>

#include "simpartner/text.h"

namespace simpartner::xml {
namespace {

static_assert(kMaxDocumentBytes <= static_cast<size_t>(INT_MAX), "libxml2 takes an int size");

// While one lives, libxml2's errors on this thread go into diagnostics; the
// handlers of before are put back at the end.
class ScopedXmlErrors {
 public:
  ScopedXmlErrors(const std::string& file_name, DiagnosticList* diagnostics)
      : file_name_(file_name),
        diagnostics_(diagnostics),
        previous_structured_(xmlStructuredError),
        previous_structured_context_(xmlStructuredErrorContext),
        previous_generic_(xmlGenericError),
        previous_generic_context_(xmlGenericErrorContext) {
    xmlSetStructuredErrorFunc(this, &ScopedXmlErrors::OnError);
    xmlSetGenericErrorFunc(this, &ScopedXmlErrors::OnGenericError);
  }
  ~ScopedXmlErrors() {
    xmlSetStructuredErrorFunc(previous_structured_context_, previous_structured_);
    xmlSetGenericErrorFunc(previous_generic_context_, previous_generic_);
  }
  ScopedXmlErrors(const ScopedXmlErrors&) = delete;
  ScopedXmlErrors& operator=(const ScopedXmlErrors&) = delete;

 private:
  static void OnError(void* self_ptr, xmlErrorPtr error) {
    auto* self = static_cast<ScopedXmlErrors*>(self_ptr);
    if (error == nullptr || error->level == XML_ERR_WARNING) return;
    // The first fatal error's line only (xml_document.h says why).
    if (self->first_fatal_line_ > 0 && error->line > self->first_fatal_line_) return;
    if (error->level == XML_ERR_FATAL && self->first_fatal_line_ == 0 && error->line > 0)
      self->first_fatal_line_ = error->line;
    // Some messages span lines ("...indicate encoding !\nBytes: 0xE9 ...");
    // a diagnostic is one line.
    std::string message = Trim(error->message != nullptr ? error->message : "XML error");
    std::replace(message.begin(), message.end(), '\n', ' ');
    const auto* node = static_cast<const xmlNode*>(error->node);
    const std::string element =
        node != nullptr && node->type == XML_ELEMENT_NODE ? Name(node) : std::string();
    self->diagnostics_->Add(self->file_name_, error->line, element, message);
  }
  // Messages without structure (rare); kept so that nothing reaches stderr.
  static void OnGenericError(void*, const char*, ...) {}

  const std::string& file_name_;
  DiagnosticList* diagnostics_;
  int first_fatal_line_ = 0;
  xmlStructuredErrorFunc previous_structured_;
  void* previous_structured_context_;
  xmlGenericErrorFunc previous_generic_;
  void* previous_generic_context_;
};

struct FreeDtd {
  void operator()(xmlDtd* dtd) const { xmlFreeDtd(dtd); }
};
struct FreeValidCtxt {
  void operator()(xmlValidCtxt* context) const { xmlFreeValidCtxt(context); }
};

// The 1-based line of the DOCTYPE in text; 0 when there is none.
int DoctypeLine(std::string_view text) {
  const size_t at = text.find("<!DOCTYPE");
  if (at == std::string_view::npos) return 0;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
}

std::string SizeText(size_t bytes) {
  return std::to_string(bytes) + " bytes (" + FormatNumber(static_cast<double>(bytes) / 1048576.0, 10) +
         " MiB)";
}

std::string Chars(const xmlChar* text) {
  return text != nullptr ? reinterpret_cast<const char*>(text) : "";
}

}  // namespace

void Document::FreeDoc::operator()(xmlDoc* doc) const { xmlFreeDoc(doc); }

Document::Document(xmlDoc* doc, std::string file_name, int doctype_line)
    : doc_(doc), file_name_(std::move(file_name)), doctype_line_(doctype_line) {}

const xmlNode* Document::root() const { return xmlDocGetRootElement(doc_.get()); }

std::optional<Document> Document::Parse(std::string_view text, const std::string& file_name,
                                        DiagnosticList* diagnostics) {
  if (text.size() > kMaxDocumentBytes) {
    diagnostics->Add(file_name, 0, "", "file is " + SizeText(text.size()) +
                                           "; XML files may have at most " +
                                           SizeText(kMaxDocumentBytes));
    return std::nullopt;
  }
  // libxml2's globals are set up once, before any thread parses (its
  // rule); a function-local static runs exactly once.
  [[maybe_unused]] static const bool initialized = (xmlInitParser(), true);
  xmlDoc* parsed = nullptr;
  {
    ScopedXmlErrors capture(file_name, diagnostics);
    // Without XML_PARSE_DTDLOAD and XML_PARSE_NOENT nothing outside the
    // text is read and no entity is expanded; NONET for good measure.
    parsed = xmlReadMemory(text.data(), static_cast<int>(text.size()), file_name.c_str(), nullptr,
                           XML_PARSE_NONET | XML_PARSE_BIG_LINES);
  }
  if (parsed == nullptr) {
    if (diagnostics->empty()) diagnostics->Add(file_name, 0, "", "not a well-formed XML file");
    return std::nullopt;
  }
  Document document(parsed, file_name, DoctypeLine(text));
  if (document.root() == nullptr) {
    diagnostics->Add(file_name, 0, "", "no root element");
    return std::nullopt;
  }
  if (parsed->intSubset != nullptr && parsed->intSubset->children != nullptr) {
    diagnostics->Add(file_name, document.doctype_line_, "DOCTYPE",
                     "declarations inside the file are not allowed; files are validated "
                     "against SimPartner's own DTD");
    return std::nullopt;
  }
  return document;
}

std::optional<Document> Document::Read(std::string_view text, const std::string& file_name,
                                       const char* root_name, const Dtd& dtd,
                                       DiagnosticList* diagnostics) {
  std::optional<Document> document = Parse(text, file_name, diagnostics);
  if (!document) return std::nullopt;
  const xmlNode* root = document->root();
  if (Name(root) != root_name) {
    AddAt(diagnostics, file_name, root, std::string("root element must be <") + root_name + ">");
    return std::nullopt;
  }
  if (!document->Validate(dtd, diagnostics)) return std::nullopt;
  return document;
}

bool Document::CheckDoctype(const Dtd& dtd, DiagnosticList* diagnostics) const {
  const xmlDtd* doctype = doc_->intSubset;
  if (doctype == nullptr) return true;
  const std::string root_name = Name(root());
  const std::string named = Chars(doctype->name);
  const std::string system = Chars(doctype->SystemID);
  const std::string how = "write <!DOCTYPE " + root_name + " SYSTEM \"" + dtd.file_name +
                          "\"> or leave the DOCTYPE out";
  std::string problem;
  if (named != root_name) {
    problem = "the DOCTYPE names <" + named + "> but the root element is <" + root_name + ">";
  } else if (doctype->ExternalID != nullptr) {
    problem = "a PUBLIC identifier ('" + Chars(doctype->ExternalID) +
              "') is not allowed; the file is validated against the built-in " + dtd.file_name +
              " (" + how + ")";
  } else if (!system.empty() && std::filesystem::path(system).filename() != dtd.file_name) {
    problem = "the DOCTYPE names '" + system + "'; the file is validated against the built-in " +
              dtd.file_name + " (" + how + ")";
  }
  if (problem.empty()) return true;
  diagnostics->Add(file_name_, doctype_line_, "DOCTYPE", problem);
  return false;
}

bool Document::Validate(const Dtd& dtd, DiagnosticList* diagnostics) const {
  if (!CheckDoctype(dtd, diagnostics)) return false;
  ScopedXmlErrors capture(file_name_, diagnostics);
  xmlParserInputBufferPtr buffer = xmlParserInputBufferCreateMem(
      dtd.text.data(), static_cast<int>(dtd.text.size()), XML_CHAR_ENCODING_NONE);
  const std::unique_ptr<xmlDtd, FreeDtd> parsed(
      xmlIOParseDTD(nullptr, buffer, XML_CHAR_ENCODING_NONE));  // takes buffer
  if (parsed == nullptr) {
    diagnostics->Add(file_name_, 0, "", "internal error: the built-in DTD does not parse");
    return false;
  }
  const std::unique_ptr<xmlValidCtxt, FreeValidCtxt> context(xmlNewValidCtxt());
  const size_t before = diagnostics->size();
  if (xmlValidateDtd(context.get(), doc_.get(), parsed.get())) return true;
  if (diagnostics->size() == before)
    diagnostics->Add(file_name_, 0, "", "does not follow the DTD " + dtd.file_name);
  return false;
}

std::string Name(const xmlNode* node) {
  return node != nullptr ? Chars(node->name) : std::string();
}

int Line(const xmlNode* node) {
  return node != nullptr ? static_cast<int>(xmlGetLineNo(node)) : 0;
}

std::optional<std::string> Attribute(const xmlNode* node, const char* name) {
  if (node == nullptr) return std::nullopt;
  xmlChar* value = xmlGetProp(node, reinterpret_cast<const xmlChar*>(name));
  if (value == nullptr) return std::nullopt;
  std::string text = Chars(value);
  xmlFree(value);
  return text;
}

const xmlNode* Child(const xmlNode* parent, const char* name) {
  if (parent == nullptr) return nullptr;
  for (const xmlNode* n = parent->children; n != nullptr; n = n->next)
    if (n->type == XML_ELEMENT_NODE && Name(n) == name) return n;
  return nullptr;
}

std::vector<const xmlNode*> Children(const xmlNode* parent, const char* name) {
  std::vector<const xmlNode*> out;
  if (parent == nullptr) return out;
  for (const xmlNode* n = parent->children; n != nullptr; n = n->next)
    if (n->type == XML_ELEMENT_NODE && (name == nullptr || Name(n) == name)) out.push_back(n);
  return out;
}

std::string RawText(const xmlNode* node) {
  if (node == nullptr) return "";
  xmlChar* content = xmlNodeGetContent(node);
  std::string text = Chars(content);
  xmlFree(content);
  return text;
}

std::string Text(const xmlNode* node) { return Trim(RawText(node)); }

void AddAt(DiagnosticList* diagnostics, const std::string& file_name, const xmlNode* node,
           const std::string& message) {
  diagnostics->Add(file_name, Line(node), Name(node), message);
}

}  // namespace simpartner::xml
