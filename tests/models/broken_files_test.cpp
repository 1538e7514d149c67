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
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "simpartner/model/loader.h"

namespace simpartner::model {
namespace {

namespace fs = std::filesystem;

const fs::path kBrokenDir = fs::path(SP_SOURCE_DIR) / "tests" / "models" / "broken";

std::string ReadText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

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
  const std::regex spec(R"(^\s*(?:<!--)?\s*(expect:\s*(?:(\S+?):)?(\d+): (.+?))\s*$)");
  std::istringstream comment(text.substr(0, end));
  std::string line;
  while (std::getline(comment, line)) {
    if (line.find("expect:") == std::string::npos) continue;
    std::smatch m;
    if (!std::regex_match(line, m, spec)) {
      *why = "cannot read expect line '" + line + "'";
      return false;
    }
    Expectation e;
    e.written = m[1].str();
    e.file = m[2].matched ? world.parent_path() / m[2].str() : world;
    e.line = std::stoi(m[3].str());
    const std::string wanted = m[4].str();
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
