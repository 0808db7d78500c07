// The checks of -options_file before PETSc reads it (src/core/options_files.hpp): each malformed file
// gets the one-line message naming its cause, a well-formed one none.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "src/core/options_files.hpp"

namespace fs = std::filesystem;

namespace {

struct OptionsFiles : ::testing::Test {
  fs::path dir = fs::temp_directory_path() / ("sph_options_files_" + std::to_string(::getpid()));
  void SetUp() override { fs::create_directories(dir); }
  void TearDown() override { fs::remove_all(dir); }
  std::string file(const std::string& name, const std::string& text) {
    const fs::path p = dir / name;
    std::ofstream(p) << text;
    return p.string();
  }
  std::string problem(const std::string& path) {
    std::vector<std::string> chain;
    return sph::options_file_problem(path, "-options_file", chain);
  }
};

TEST_F(OptionsFiles, WordsSplitAsPetscDoesWithQuotedWordsKept) {
  EXPECT_EQ(sph::options_file_words("  -a 1\t-b  \"x y\" \n"), (std::vector<std::string>{"-a", "1", "-b", "x y"}));
  EXPECT_TRUE(sph::options_file_words(" \t\r\n").empty());
}

TEST_F(OptionsFiles, AWellFormedFileWithCommentsAndIncludesHasNoProblem) {
  const std::string inner = file("inner.opts", "-nx 32\n");
  EXPECT_EQ(problem(file("ok.opts", "# a comment\n-case taylor_green # trailing\n\n-options_file " + inner + "\n")),
            "");
}

TEST_F(OptionsFiles, EachMalformedFileNamesItsCauseAndLine) {
  EXPECT_NE(problem(file("word.opts", "-nx 4\nnx 32\n")).find("line 2: 'nx' is not an option"), std::string::npos);
  EXPECT_NE(problem(file("two.opts", "-nx 32 -re 100\n")).find("put each option on a line of its own"),
            std::string::npos);
  EXPECT_NE(problem((dir / "missing.opts").string()).find("cannot read options file"), std::string::npos);
  EXPECT_NE(problem(dir.string()).find("is a folder"), std::string::npos);
}

TEST_F(OptionsFiles, AFileThatIncludesItselfIsRefusedNotFollowed) {
  const std::string loop = (dir / "loop.opts").string();
  file("loop.opts", "-options_file " + loop + "\n");
  EXPECT_NE(problem(loop).find("includes itself"), std::string::npos);
  // The error is found in an included file too, and named there.
  const std::string bad = file("bad.opts", "oops\n");
  EXPECT_NE(problem(file("outer.opts", "-options_file " + bad + "\n")).find("bad.opts' line 1"), std::string::npos);
}

TEST_F(OptionsFiles, OnlyHelpAndVersionOnlyPrint) {
  const char* help[] = {"sph", "-nx", "8", "-help"};
  const char* run[] = {"sph", "-nx", "8"};
  EXPECT_TRUE(sph::only_prints(4, const_cast<char**>(help)));
  EXPECT_FALSE(sph::only_prints(3, const_cast<char**>(run)));
}

}  // namespace
