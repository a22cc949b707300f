// Whole-file reads and all-or-nothing writes: only regular files are read, at
// most the bytes asked for; an output path that exists and is not a regular
// file is refused, not replaced; output locations are checked before work.

#include "temp_dir_test_util.h"

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

namespace sierra {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class CoreFiles : public test::TempDirTest {
  protected:
    // Names in the directory that look like leftover temporary files.
    int leftovers() const {
        int n = 0;
        for (const auto& entry : fs::directory_iterator(dir_))
            n += entry.path().filename().string().find(".tmp-") != std::string::npos;
        return n;
    }
};

TEST_F(CoreFiles, ReadsRegularFilesUpToALimit) {
    writeFileAtomic(path("a.bin"), std::string_view("hello"));
    const auto bytes = readFileBytes(path("a.bin"));
    EXPECT_EQ(std::string(bytes.begin(), bytes.end()), "hello");
    EXPECT_EQ(regularFileSize(path("a.bin")), 5u);
    EXPECT_EQ(readFileBytes(path("a.bin"), 5).size(), 5u);
    EXPECT_THAT(errorOf([&] { readFileBytes(path("a.bin"), 4, "a test file is at most 4 bytes"); }),
                HasSubstr(path("a.bin") + " has 5 bytes, more than the 4 bytes allowed; a test "
                                          "file is at most 4 bytes"));
    EXPECT_THAT(errorOf([&] { readFileBytes(path("missing")); }),
                HasSubstr("cannot open " + path("missing") + ": No such file or directory"));
    ASSERT_EQ(mkfifo(path("fifo").c_str(), 0600), 0);
    EXPECT_THAT(errorOf([&] { readFileBytes(path("fifo")); }),
                HasSubstr("it is a FIFO (named pipe); expected a regular file"));
    EXPECT_THAT(errorOf([&] { regularFileSize(path("fifo")); }), HasSubstr("it is a FIFO"));
    fs::create_symlink("/dev/zero", path("zero"));
    EXPECT_THAT(errorOf([&] { readFileBytes(path("zero")); }),
                HasSubstr("it is a character device; expected a regular file"));
    EXPECT_THAT(errorOf([&] { readFileBytes(dir_.string()); }), HasSubstr("it is a directory"));
    // A symlink to a regular file is read through.
    fs::create_symlink(path("a.bin"), path("link.bin"));
    EXPECT_EQ(readFileBytes(path("link.bin")).size(), 5u);
}

TEST_F(CoreFiles, WriteReplacesRegularFilesOnly) {
    writeFileAtomic(path("out.txt"), std::string_view("one"));
    writeFileAtomic(path("out.txt"), std::string_view("two"));
    EXPECT_EQ(read(path("out.txt")), "two");

    // A symlink: renaming over it would replace the link, not write its target.
    writeFileAtomic(path("target.txt"), std::string_view("target"));
    fs::create_symlink(path("target.txt"), path("link.txt"));
    EXPECT_THAT(errorOf([&] { writeFileAtomic(path("link.txt"), std::string_view("x")); }),
                HasSubstr("cannot write " + path("link.txt") +
                          ": it exists and is a symbolic link, not a regular file"));
    EXPECT_TRUE(fs::is_symlink(path("link.txt")));
    EXPECT_EQ(read(path("target.txt")), "target");

    ASSERT_EQ(mkfifo(path("fifo").c_str(), 0600), 0);
    EXPECT_THAT(errorOf([&] { writeFileAtomic(path("fifo"), std::string_view("x")); }),
                HasSubstr("it exists and is a FIFO (named pipe), not a regular file"));
    EXPECT_TRUE(fs::is_fifo(path("fifo")));

    fs::create_directory(path("dir"));
    EXPECT_THAT(errorOf([&] { writeFileAtomic(path("dir"), std::string_view("x")); }),
                HasSubstr("it exists and is a directory"));
    fs::create_symlink("/dev/null", path("null"));
    EXPECT_THAT(errorOf([&] { writeFileAtomic(path("null"), std::string_view("x")); }),
                HasSubstr("it exists and is a symbolic link"));
    EXPECT_EQ(leftovers(), 0);

    // A writer that throws leaves neither the file nor a temporary one.
    EXPECT_THROW(writeFileAtomic(path("thrown.txt"), [](std::FILE*) { throw Error("boom"); }),
                 Error);
    EXPECT_FALSE(fs::exists(path("thrown.txt")));
    EXPECT_EQ(leftovers(), 0);
}

TEST_F(CoreFiles, EnsureWritableLocationCreatesOrRefusesEarly) {
    ensureWritableLocation(path("a/b/c/out.png"));
    EXPECT_TRUE(fs::is_directory(path("a/b/c")));
    EXPECT_FALSE(fs::exists(path("a/b/c/out.png")));
    writeFileAtomic(path("a/b/c/out.png"), std::string_view("x"));  // then succeeds
    ensureWritableLocation(path("a/b/c/out.png"));                  // an existing file is fine

    writeFileAtomic(path("file"), std::string_view("x"));
    EXPECT_THAT(errorOf([&] { ensureWritableLocation(path("file/out.png")); }),
                HasSubstr("cannot write " + path("file/out.png") +
                          ": cannot create the directory " + path("file")));
    fs::create_directory(path("dir"));
    EXPECT_THAT(errorOf([&] { ensureWritableLocation(path("dir")); }),
                HasSubstr("it exists and is a directory, not a regular file"));
    ASSERT_EQ(mkfifo(path("fifo").c_str(), 0600), 0);
    EXPECT_THAT(errorOf([&] { ensureWritableLocation(path("fifo")); }), HasSubstr("FIFO"));
    // A bare name means the working directory, which exists.
    EXPECT_NO_THROW(ensureWritableLocation("sierra_core_files_bare_name.png"));
}

TEST(CoreFilesExtension, IsTheFileNamesLastDotOnInLowerCase) {
    EXPECT_EQ(lowerExtension("out/Frame.PNG"), ".png");
    EXPECT_EQ(lowerExtension("a.b/mesh.tar.OBJ"), ".obj");
    EXPECT_EQ(lowerExtension("dir.png/frame"), "");  // a dot in a folder is not the file's
    EXPECT_EQ(lowerExtension("frame"), "");
    EXPECT_EQ(lowerExtension(""), "");
}

}  // namespace
}  // namespace sierra
