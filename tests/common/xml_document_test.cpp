// The XML reading layer (common/.../xml_document.h): lines, libxml2's
// messages, the DOCTYPE policy both ways, the size and entity limits, and
// validation against a DTD given as text.
#include <gtest/gtest.h>
#include <libxml/globals.h>
#include <libxml/xmlerror.h>

#include <string>
#include <thread>
#include <vector>

#include "simpartner/xml_document.h"

namespace simpartner::xml {
namespace {

const Dtd kShelfDtd{"shelf.dtd", R"(<!ELEMENT shelf (book*)>
<!ATTLIST shelf name CDATA #IMPLIED>
<!ELEMENT book (#PCDATA)>
<!ATTLIST book title CDATA #REQUIRED>)"};

// The one diagnostic of a failed read, as "line: element: message".
std::string OnlyProblem(const DiagnosticList& diagnostics) {
  if (diagnostics.size() != 1) return "expected one diagnostic, got:\n" + diagnostics.Format();
  const Diagnostic& d = diagnostics.items()[0];
  return std::to_string(d.line) + ": " + d.element + ": " + d.message;
}

TEST(XmlDocument, NodesKeepTheirLinesNamesAttributesAndText) {
  const std::string text = R"(<?xml version="1.0"?>
<shelf name="top">
  <!-- a comment is not an element -->
  <book title="A">  first
    text </book>
  <book title="B"/>
</shelf>
)";
  DiagnosticList diagnostics;
  const std::optional<Document> doc = Document::Parse(text, "shelf.xml", &diagnostics);
  ASSERT_TRUE(doc) << diagnostics.Format();
  EXPECT_TRUE(diagnostics.empty());
  EXPECT_EQ(doc->file_name(), "shelf.xml");
  const xmlNode* root = doc->root();
  EXPECT_EQ(Name(root), "shelf");
  EXPECT_EQ(Line(root), 2);
  EXPECT_EQ(Attribute(root, "name"), "top");
  EXPECT_EQ(Attribute(root, "colour"), std::nullopt);
  const std::vector<const xmlNode*> books = Children(root, "book");
  ASSERT_EQ(books.size(), 2u);
  EXPECT_EQ(Children(root).size(), 2u);  // elements only
  EXPECT_EQ(Line(books[0]), 4);
  EXPECT_EQ(Line(books[1]), 6);
  EXPECT_EQ(Child(root, "book"), books[0]);
  EXPECT_EQ(Child(root, "lamp"), nullptr);
  EXPECT_EQ(Text(books[0]), "first\n    text");
  EXPECT_EQ(RawText(books[0]), "  first\n    text ");
  EXPECT_EQ(Text(books[1]), "");
  // Null in, nothing out.
  EXPECT_EQ(Name(nullptr), "");
  EXPECT_EQ(Line(nullptr), 0);
  EXPECT_EQ(Child(nullptr, "book"), nullptr);
  EXPECT_TRUE(Children(nullptr).empty());
  EXPECT_EQ(Text(nullptr), "");
  DiagnosticList at;
  AddAt(&at, "shelf.xml", books[1], "too thin");
  EXPECT_EQ(at.Format(), "shelf.xml:6: book: too thin");
}

TEST(XmlDocument, NotWellFormedKeepsOnlyTheFirstFatalErrorsLine) {
  // libxml2 reads on after the mismatch at line 3 and complains about the
  // end of the file too; only line 3 is reported.
  const std::string text = "<shelf>\n  <book title=\"A\">\n  </bok>\n  <book/>\n</shelf>\n";
  DiagnosticList diagnostics;
  EXPECT_FALSE(Document::Parse(text, "bad.xml", &diagnostics));
  ASSERT_FALSE(diagnostics.empty());
  for (const Diagnostic& d : diagnostics.items()) {
    EXPECT_EQ(d.file, "bad.xml");
    EXPECT_EQ(d.line, 3) << d.Format();
  }
  EXPECT_EQ(diagnostics.items()[0].message,
            "Opening and ending tag mismatch: book line 2 and bok");
}

TEST(XmlDocument, MultiLineMessagesBecomeOneLine) {
  const std::string text = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<shelf name=\"caf\xE9\"/>\n";
  DiagnosticList diagnostics;
  EXPECT_FALSE(Document::Parse(text, "latin1.xml", &diagnostics));
  ASSERT_FALSE(diagnostics.empty());
  EXPECT_EQ(diagnostics.items()[0].line, 2);
  EXPECT_NE(diagnostics.items()[0].message.find("Input is not proper UTF-8"), std::string::npos)
      << diagnostics.Format();
  for (const Diagnostic& d : diagnostics.items())
    EXPECT_EQ(d.message.find('\n'), std::string::npos) << d.message;
}

TEST(XmlDocument, EmptyTextHasNoDocument) {
  DiagnosticList diagnostics;
  EXPECT_FALSE(Document::Parse("", "empty.xml", &diagnostics));
  ASSERT_FALSE(diagnostics.empty());
  EXPECT_EQ(diagnostics.items()[0].file, "empty.xml");
}

TEST(XmlDocument, DoctypesThatOnlyNameOurDtdAreAccepted) {
  for (const std::string doctype :
       {"", "<!DOCTYPE shelf>\n", "<!DOCTYPE shelf []>\n", "<!DOCTYPE shelf SYSTEM \"shelf.dtd\">\n",
        "<!DOCTYPE shelf SYSTEM \"../dtd/shelf.dtd\">\n"}) {
    const std::string text = "<?xml version=\"1.0\"?>\n" + doctype + "<shelf><book title=\"A\"/></shelf>\n";
    DiagnosticList diagnostics;
    const std::optional<Document> doc =
        Document::Read(text, "ok.xml", "shelf", kShelfDtd, &diagnostics);
    EXPECT_TRUE(doc) << doctype << diagnostics.Format();
    EXPECT_TRUE(diagnostics.empty()) << doctype << diagnostics.Format();
  }
}

TEST(XmlDocument, DeclarationsInTheFileAreRefusedAtTheirLine) {
  // An attribute the DTD does not allow, declared by the file itself.
  const std::string text = "<?xml version=\"1.0\"?>\n\n<!DOCTYPE shelf [\n"
                           "  <!ATTLIST book price CDATA #IMPLIED>\n]>\n"
                           "<shelf><book title=\"A\" price=\"9\"/></shelf>\n";
  DiagnosticList diagnostics;
  EXPECT_FALSE(Document::Parse(text, "own.xml", &diagnostics));
  EXPECT_EQ(OnlyProblem(diagnostics),
            "3: DOCTYPE: declarations inside the file are not allowed; files are validated "
            "against SimPartner's own DTD");
}

TEST(XmlDocument, OtherDoctypesAreRefusedAtValidation) {
  struct Case {
    std::string doctype;
    std::string problem;
  };
  const std::vector<Case> cases = {
      {"<!DOCTYPE book>", "the DOCTYPE names <book> but the root element is <shelf>"},
      {"<!DOCTYPE shelf PUBLIC \"-//Shelf//EN\" \"shelf.dtd\">",
       "a PUBLIC identifier ('-//Shelf//EN') is not allowed; the file is validated against the "
       "built-in shelf.dtd (write <!DOCTYPE shelf SYSTEM \"shelf.dtd\"> or leave the DOCTYPE out)"},
      {"<!DOCTYPE shelf SYSTEM \"http://example.org/wide.dtd\">",
       "the DOCTYPE names 'http://example.org/wide.dtd'; the file is validated against the "
       "built-in shelf.dtd (write <!DOCTYPE shelf SYSTEM \"shelf.dtd\"> or leave the DOCTYPE "
       "out)"},
  };
  for (const Case& c : cases) {
    const std::string text = "<?xml version=\"1.0\"?>\n" + c.doctype + "\n<shelf/>\n";
    DiagnosticList diagnostics;
    std::optional<Document> doc = Document::Parse(text, "doc.xml", &diagnostics);
    ASSERT_TRUE(doc) << c.doctype << diagnostics.Format();
    EXPECT_FALSE(doc->Validate(kShelfDtd, &diagnostics));
    EXPECT_EQ(OnlyProblem(diagnostics), "2: DOCTYPE: " + c.problem);
  }
}

TEST(XmlDocument, EntitiesAreNeitherDeclaredNorExpanded) {
  // A declared entity, internal or external, comes with declarations.
  for (const std::string entity :
       {"<!ENTITY x \"lol lol lol\">", "<!ENTITY x SYSTEM \"file:///etc/passwd\">"}) {
    const std::string text = "<!DOCTYPE shelf [ " + entity + " ]>\n<shelf>&x;</shelf>\n";
    DiagnosticList diagnostics;
    EXPECT_FALSE(Document::Parse(text, "entity.xml", &diagnostics));
    ASSERT_FALSE(diagnostics.empty());
    EXPECT_EQ(diagnostics.items().back().element, "DOCTYPE") << diagnostics.Format();
    EXPECT_EQ(diagnostics.items().back().line, 1) << diagnostics.Format();
  }
  // One that is not declared is an error of its own; the predefined ones
  // are text.
  DiagnosticList diagnostics;
  EXPECT_FALSE(Document::Parse("<shelf>\n<book title=\"A\">&lol;</book></shelf>\n", "undeclared.xml",
                               &diagnostics));
  ASSERT_FALSE(diagnostics.empty());
  EXPECT_EQ(diagnostics.items()[0].line, 2);
  EXPECT_EQ(diagnostics.items()[0].message, "Entity 'lol' not defined");
  DiagnosticList fine;
  const std::optional<Document> doc =
      Document::Parse("<shelf><book title=\"A\">&lt;&amp;&#65;</book></shelf>", "fine.xml", &fine);
  ASSERT_TRUE(doc) << fine.Format();
  EXPECT_EQ(Text(Child(doc->root(), "book")), "<&A");
}

TEST(XmlDocument, TooLargeIsRefusedUnread) {
  std::string text = "<shelf>";
  text.resize(kMaxDocumentBytes + 1, ' ');
  DiagnosticList diagnostics;
  EXPECT_FALSE(Document::Parse(text, "huge.xml", &diagnostics));
  EXPECT_EQ(OnlyProblem(diagnostics),
            "0: : file is 67108865 bytes (64.00000095 MiB); XML files may have at most 67108864 "
            "bytes (64 MiB)");
}

TEST(XmlDocument, ValidationNamesTheElementAndLine) {
  const std::string text = "<shelf>\n  <book title=\"A\"/>\n  <book/>\n  <lamp/>\n</shelf>\n";
  DiagnosticList diagnostics;
  EXPECT_FALSE(Document::Read(text, "shelf.xml", "shelf", kShelfDtd, &diagnostics));
  ASSERT_FALSE(diagnostics.empty());
  const std::string all = diagnostics.Format();
  EXPECT_NE(all.find("shelf.xml:3: book: Element book does not carry attribute title"),
            std::string::npos)
      << all;
  EXPECT_NE(all.find("shelf.xml:4: lamp: No declaration for element lamp"), std::string::npos)
      << all;
}

TEST(XmlDocument, ReadWantsItsRootElement) {
  DiagnosticList diagnostics;
  EXPECT_FALSE(Document::Read("<?xml version=\"1.0\"?>\n<book title=\"A\"/>", "book.xml", "shelf",
                              kShelfDtd, &diagnostics));
  EXPECT_EQ(OnlyProblem(diagnostics), "2: book: root element must be <shelf>");
}

int g_outside_errors = 0;
void CountOutsideError(void*, xmlErrorPtr) { ++g_outside_errors; }

TEST(XmlDocument, LibxmlHandlerIsPutBackAfterwards) {
  int context = 0;
  xmlSetStructuredErrorFunc(&context, &CountOutsideError);
  DiagnosticList diagnostics;
  EXPECT_FALSE(Document::Parse("<shelf>", "open.xml", &diagnostics));
  EXPECT_FALSE(diagnostics.empty());
  EXPECT_EQ(g_outside_errors, 0);  // ours got them
  EXPECT_EQ(xmlStructuredError, &CountOutsideError);
  EXPECT_EQ(xmlStructuredErrorContext, &context);
  xmlSetStructuredErrorFunc(nullptr, nullptr);
}

TEST(XmlDocument, ThreadsKeepTheirOwnDiagnostics) {
  // libxml2's handler is per thread: each thread's errors stay its own.
  std::vector<DiagnosticList> found(4);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([t, &found] {
      const std::string text = std::string(static_cast<size_t>(t + 1), '\n') + "<shelf><a></b></shelf>";
      for (int round = 0; round < 50; ++round) {
        DiagnosticList diagnostics;
        Document::Parse(text, "t" + std::to_string(t) + ".xml", &diagnostics);
        if (round == 0) found[static_cast<size_t>(t)] = diagnostics;
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (int t = 0; t < 4; ++t) {
    ASSERT_FALSE(found[static_cast<size_t>(t)].empty());
    for (const Diagnostic& d : found[static_cast<size_t>(t)].items()) {
      EXPECT_EQ(d.file, "t" + std::to_string(t) + ".xml");
      EXPECT_EQ(d.line, t + 2);
    }
  }
}

}  // namespace
}  // namespace simpartner::xml
