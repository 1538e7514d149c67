// The corpus of broken model files (tests/models/broken/): each world file
// there breaks one rule and says in its opening comment what a user must be
// told, as lines of the form
//
//   expect: LINE: TEXT              a problem at LINE of this file
//   expect: PATH:LINE: TEXT         a problem in PATH (relative to this
//                                   file, e.g. a robot it places); LINE 0
//                                   when the problem has no line
//
// TEXT must appear in the formatted diagnostic ("file:line: element:
// message"); " ... " separates pieces that must appear in that order. The
// files are loaded exactly as `simpartner-sim --check` loads its
// environment, and the load must report these problems and nothing else.
// Broken robots live in broken/robots/, each placed by one world file.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "simpartner/model/loader.h"
#include "../support/text_file.h"

namespace simpartner::model {
namespace {

namespace fs = std::filesystem;

const fs::path kBrokenDir = fs::path(SP_SOURCE_DIR) / "tests" / "models" / "broken";

using test_support::ReadText;

// The test cases: the world files directly in broken/ (robots/ holds what
// they place), sorted so that runs are reproducible.
std::vector<fs::path> BrokenWorldFiles() {
  std::vector<fs::path> files;
  if (!fs::is_directory(kBrokenDir)) return files;
  for (const fs::directory_entry& entry : fs::directory_iterator(kBrokenDir))
    if (entry.is_regular_file() && entry.path().extension() == ".xml")
      files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

struct Expectation {
  std::string written;                  // the expect line as written
  fs::path file;                        // the file the problem is in
  int line = 0;
  std::vector<std::string> fragments;   // in order in the formatted text
};

// Parses the expect lines of the file's opening comment; false with a
// reason when the comment is missing or malformed.
bool ReadExpectations(const fs::path& world, std::vector<Expectation>* out, std::string* why) {
  const std::string text = ReadText(world);
  if (text.rfind("<!--", 0) != 0) {
    *why = "the file does not start with an <!-- expect: ... --> comment";
    return false;
  }
  const size_t end = text.find("-->");
  if (end == std::string::npos) {
    *why = "the opening comment is not closed";
    return false;
  }
  // "[<!--] expect: [PATH:]LINE: TEXT" (parsed by hand: GCC 12 warns
  // inside <regex> under -O2 with sanitizers, and warnings are errors).
  auto trim = [](std::string s) {
    const size_t b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
  };
  auto all_digits = [](const std::string& s) {
    return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
  };
  std::istringstream comment(text.substr(0, end));
  std::string line;
  while (std::getline(comment, line)) {
    const size_t at = line.find("expect:");
    if (at == std::string::npos) continue;
    std::string before = trim(line.substr(0, at));
    if (before.rfind("<!--", 0) == 0) before = trim(before.substr(4));
    const std::string written = trim(line.substr(at));
    const std::string rest = trim(written.substr(7));
    const size_t colon_space = rest.find(": ");
    const std::string head = rest.substr(0, colon_space);
    const size_t last_colon = head.rfind(':');
    const std::string path = last_colon == std::string::npos ? "" : head.substr(0, last_colon);
    const std::string number = head.substr(last_colon == std::string::npos ? 0 : last_colon + 1);
    if (!before.empty() || colon_space == std::string::npos || !all_digits(number) ||
        path.find_first_of(" \t") != std::string::npos) {
      *why = "cannot read expect line '" + line + "'";
      return false;
    }
    Expectation e;
    e.written = written;
    e.file = path.empty() ? world : world.parent_path() / path;
    e.line = std::stoi(number);
    const std::string wanted = rest.substr(colon_space + 2);
    for (size_t from = 0;;) {
      const size_t gap = wanted.find(" ... ", from);
      e.fragments.push_back(wanted.substr(from, gap - from));
      if (gap == std::string::npos) break;
      from = gap + 5;
    }
    out->push_back(e);
  }
  if (out->empty()) {
    *why = "the opening comment has no expect line";
    return false;
  }
  return true;
}

bool SameFile(const std::string& a, const fs::path& b) {
  std::error_code ignored;
  return fs::weakly_canonical(a, ignored) == fs::weakly_canonical(b, ignored);
}

// A diagnostic meets an expectation when it is about that file and line,
// its formatted text starts with "file:line: " as the user sees it, and the
// fragments follow each other in it.
bool Meets(const Diagnostic& d, const Expectation& e) {
  if (d.line != e.line || !SameFile(d.file, e.file)) return false;
  const std::string formatted = d.Format();
  const std::string prefix = d.file + (d.line > 0 ? ":" + std::to_string(d.line) : "") + ": ";
  if (formatted.rfind(prefix, 0) != 0) return false;
  size_t at = prefix.size();
  for (const std::string& fragment : e.fragments) {
    at = formatted.find(fragment, at);
    if (at == std::string::npos) return false;
    at += fragment.size();
  }
  return true;
}

class BrokenFile : public ::testing::TestWithParam<fs::path> {};

TEST_P(BrokenFile, FailsWithTheExpectedProblemsOnly) {
  const fs::path& world = GetParam();
  std::vector<Expectation> expectations;
  std::string why;
  ASSERT_TRUE(ReadExpectations(world, &expectations, &why)) << world << ": " << why;

  // What `simpartner-sim --check --environment=FILE` does.
  const WorldLoadResult result = LoadWorldFile(world.string());
  EXPECT_FALSE(result.world.has_value()) << world << " loaded although it is broken";
  const std::vector<Diagnostic>& found = result.diagnostics.items();
  const std::string all = result.diagnostics.Format();

  std::vector<bool> used(found.size(), false);
  for (const Expectation& e : expectations) {
    bool met = false;
    for (size_t i = 0; i < found.size() && !met; ++i) {
      if (!used[i] && Meets(found[i], e)) used[i] = met = true;
    }
    EXPECT_TRUE(met) << "missing: " << e.written << "\nreported:\n" << all;
  }
  for (size_t i = 0; i < found.size(); ++i) {
    EXPECT_TRUE(used[i]) << "not expected: " << found[i].Format() << "\nfor " << world;
    // One problem, one line: nothing a user greps for may wrap.
    EXPECT_EQ(found[i].Format().find('\n'), std::string::npos) << found[i].Format();
  }
}

std::string TestName(const ::testing::TestParamInfo<fs::path>& info) {
  std::string name = info.param.stem().string();
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Corpus, BrokenFile, ::testing::ValuesIn(BrokenWorldFiles()), TestName);

// An emptied or misplaced corpus must not pass by testing nothing.
TEST(BrokenCorpus, HasAtLeastThirtyFiles) {
  EXPECT_GE(BrokenWorldFiles().size(), 30u) << "in " << kBrokenDir;
}

// The broken robots are copies of this one with one defect each, so it must
// itself be valid for each of them to test only its defect.
TEST(BrokenCorpus, BaseRobotIsValid) {
  const RobotLoadResult result = LoadRobotFile((kBrokenDir / "robots" / "two_link.xml").string());
  EXPECT_TRUE(result.robot.has_value()) << result.diagnostics.Format();
}

// Every broken robot is placed by some world of the corpus (otherwise its
// defect is never tested).
TEST(BrokenCorpus, EveryBrokenRobotIsPlaced) {
  std::string worlds;
  for (const fs::path& world : BrokenWorldFiles()) worlds += ReadText(world);
  for (const fs::directory_entry& entry : fs::directory_iterator(kBrokenDir / "robots")) {
    const std::string placed = "file=\"robots/" + entry.path().filename().string() + "\"";
    EXPECT_NE(worlds.find(placed), std::string::npos)
        << entry.path() << " is not placed by any world in " << kBrokenDir;
  }
}

}  // namespace
}  // namespace simpartner::model
