// A fresh folder per test, removed afterwards, and a way to run the `pdd`
// binary in it with its output captured.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace pdd::test {

// What a command did: its exit code (-1 when it did not exit), stdout, stderr.
struct Outcome {
  int code = -1;
  std::string out;
  std::string err;
};

class ScratchDirTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  static std::string slurp(const std::string& file);
  std::string write_file(const std::string& name, const std::string& content) const;
  // Every entry of the folder, hidden temporaries included, sorted.
  std::vector<std::string> entries() const;
  // Runs `binary args` with stdout and stderr captured (the capture files are removed).
  Outcome run(const std::string& binary, const std::string& args) const;

  std::filesystem::path dir_;
};

}  // namespace pdd::test
