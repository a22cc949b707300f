#pragma once
// A test fixture with a fresh temporary directory per test, and the file and
// error helpers the unit tests of loaders and scene files share.

#include <sierra/core/Error.h>

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace sierra::test {

class TempDirTest : public ::testing::Test {
  protected:
    using Bytes = std::vector<uint8_t>;

    // <tmp>/sierra_<suite>_<pid>_<test>: tests that ctest runs in parallel
    // processes never share a directory.
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = std::filesystem::temp_directory_path() /
               (std::string("sierra_") + info->test_suite_name() + "_" +
                std::to_string(::getpid()) + "_" + info->name());
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    // Writes `bytes` to `name` in the directory; returns its path.
    std::string write(const std::string& name, const Bytes& bytes) const {
        std::ofstream out(path(name), std::ios::binary);
        out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        return path(name);
    }
    std::string write(const std::string& name, const std::string& text) const {
        return write(name, Bytes(text.begin(), text.end()));
    }

    static std::string read(const std::string& file) {
        std::ifstream in(file, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    }

    // The message of the sierra::Error that `f` throws, or `none` when it throws nothing.
    template <typename F>
    static std::string errorOf(F&& f, const std::string& none = "") {
        try {
            f();
        } catch (const Error& e) {
            return e.what();
        }
        return none;
    }

    std::filesystem::path dir_;
};

}  // namespace sierra::test
