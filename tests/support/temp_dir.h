// SPDX-License-Identifier: Apache-2.0
// phasor test support — a fresh, empty directory per test (removed afterwards), for tests that
// write files and check that nothing else (temporaries, partial outputs) is left behind.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

namespace phasor::test {

class TempDirTest : public testing::Test {
  protected:
    /// `prefix` names the directory: <gtest temp dir>/<prefix>_<test name>_<pid>.
    explicit TempDirTest(std::string prefix) : prefix_(std::move(prefix)) {}
    void SetUp() override {
        const auto *info = testing::UnitTest::GetInstance()->current_test_info();
        dir_ = std::filesystem::path(testing::TempDir()) /
               (prefix_ + "_" + std::string(info->name()) + "_" + std::to_string(getpid()));
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::string Path(const std::string &name) const { return (dir_ / name).string(); }
    /// File names in the directory.
    std::vector<std::string> Listing() const {
        std::vector<std::string> names;
        for (const auto &e : std::filesystem::directory_iterator(dir_)) names.push_back(e.path().filename());
        return names;
    }
    std::filesystem::path dir_;

  private:
    std::string prefix_;
};

}  // namespace phasor::test
