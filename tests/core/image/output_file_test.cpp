// SPDX-License-Identifier: Apache-2.0
// All-or-nothing output files (core/image/output_file.h): exact bytes on success; on a failed write —
// simulated with a file-size limit (RLIMIT_FSIZE makes write(2) fail with EFBIG exactly where a
// full disk fails with ENOSPC) — an error naming the file and nothing left behind, for raw files
// and for every image writer (EXR, PNG, false-colour PNG).

#include <sys/resource.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/diagnostics.h"
#include "core/image/image_io.h"
#include "core/image/output_file.h"
#include "support/stats.h"
#include "support/temp_dir.h"

namespace phasor {
namespace {

class OutputFileTest : public test::TempDirTest {
  protected:
    OutputFileTest() : TempDirTest("phasor_output_file") {}
};

std::string Contents(const std::string &path) {
    std::ifstream f(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), {});
}

// Limits the size of files this process writes to `bytes` while in scope; SIGXFSZ is ignored so
// that the write that would exceed it fails with EFBIG instead of killing the test.
class FileSizeLimit {
  public:
    explicit FileSizeLimit(rlim_t bytes) {
        getrlimit(RLIMIT_FSIZE, &old_);
        rlimit l = old_;
        l.rlim_cur = bytes;
        EXPECT_EQ(setrlimit(RLIMIT_FSIZE, &l), 0);
        oldHandler_ = std::signal(SIGXFSZ, SIG_IGN);
    }
    ~FileSizeLimit() {
        setrlimit(RLIMIT_FSIZE, &old_);
        std::signal(SIGXFSZ, oldHandler_);
    }

  private:
    rlimit old_{};
    void (*oldHandler_)(int) = SIG_DFL;
};

// Expects `write` to throw "cannot write 'PATH': File too large".
template <typename F>
void ExpectTooLarge(const std::string &path, F write) {
    try {
        write();
        ADD_FAILURE() << "expected phasor::Error for " << path;
    } catch (const Error &e) {
        EXPECT_EQ(e.Message(), "cannot write '" + path + "': File too large");
    }
}

// A noisy RGB image: it compresses badly, so its PNG and EXR are far larger than the limits below.
Image Noise(int w, int h) {
    Image img{w, h, {"R", "G", "B", "intensity"}, std::vector<float>(std::size_t(w) * h * 4), {}};
    test::TestRng rng(7);
    for (float &v : img.data) v = float(rng.Uniform());
    return img;
}

TEST_F(OutputFileTest, CommittedFilesHoldExactlyTheBytes) {
    std::string binary("a\0b\nc", 5);
    OutputFiles files;
    files.Stage(Path("one.csv"), "x,y\n1,2\n");
    files.Stage(Path("two.bin"), binary);
    EXPECT_EQ(Listing().size(), 2u);  // the temporaries
    files.Commit();
    EXPECT_EQ(Contents(Path("one.csv")), "x,y\n1,2\n");
    EXPECT_EQ(Contents(Path("two.bin")), binary);
    EXPECT_EQ(Listing().size(), 2u);
}

TEST_F(OutputFileTest, UncommittedFilesLeaveNothing) {
    {
        OutputFiles files;
        files.Stage(Path("a.csv"), "1\n");
    }
    EXPECT_TRUE(Listing().empty());
}

TEST_F(OutputFileTest, AFailedFileRemovesTheWholeSetAndKeepsOlderFiles) {
    WriteFileAtomically(Path("big.csv"), "old\n");  // from an earlier run: must survive
    OutputFiles files;
    files.Stage(Path("small.csv"), "fits\n");
    {
        FileSizeLimit limit(1000);
        ExpectTooLarge(Path("big.csv"), [&] { files.Stage(Path("big.csv"), std::string(5000, 'x')); });
    }
    files.Commit();  // nothing left to commit
    EXPECT_EQ(Listing(), std::vector<std::string>{"big.csv"});
    EXPECT_EQ(Contents(Path("big.csv")), "old\n");
}

// A file written by another writer (a plot drawn by a child process) at the temporary path
// StageWritten gives it: committed with the others, dropped when the writer declines, and
// an error of the writer removes the whole set.
TEST_F(OutputFileTest, FilesWrittenByAnotherWriterJoinTheSet) {
    OutputFiles files;
    files.Stage(Path("data.csv"), "x\n");
    std::string seen;
    EXPECT_TRUE(files.StageWritten(Path("plot.svg"), [&](const std::string &temp) {
        seen = temp;
        EXPECT_TRUE(std::filesystem::exists(temp));  // created empty, for the writer to fill
        EXPECT_NE(temp, Path("plot.svg"));
        std::ofstream(temp) << "<svg/>";
        return true;
    }));
    EXPECT_FALSE(std::filesystem::exists(Path("plot.svg")));
    // A writer that declines (e.g. matplotlib is missing): nothing staged, the rest kept.
    EXPECT_FALSE(files.StageWritten(Path("other.png"), [](const std::string &) { return false; }));
    files.Commit();
    EXPECT_EQ(Contents(Path("plot.svg")), "<svg/>");
    EXPECT_EQ(Contents(Path("data.csv")), "x\n");
    EXPECT_FALSE(std::filesystem::exists(seen));
    EXPECT_EQ(Listing().size(), 2u);

    OutputFiles failing;
    failing.Stage(Path("a.csv"), "new\n");
    EXPECT_THROW(failing.StageWritten(Path("b.png"),
                                      [](const std::string &temp) -> bool {
                                          std::ofstream(temp) << "partial";
                                          throw Error("cannot write 'b.png': the plot failed");
                                      }),
                 Error);
    failing.Commit();  // nothing left to commit
    EXPECT_EQ(Listing().size(), 2u) << "a temporary or a partial file was left";
}

TEST_F(OutputFileTest, DirectoryTargetsAreRefused) {
    EXPECT_THROW(WriteFileAtomically(dir_.string() + "/", "x"), Error);
    EXPECT_THROW(WriteFileAtomically(Path("missing/a.csv"), "x"), Error);
    EXPECT_TRUE(Listing().empty());
}

// The image writers, each given a file-size limit far below the file's size: an error naming the
// file, and no target, no temporary. (A PNG cut short by a full disk used to be reported as
// written: libpng's writer did not report the failed write.)
TEST_F(OutputFileTest, ImagesThatDoNotFitAreErrorsAndLeaveNothing) {
    const Image img = Noise(96, 64);
    FileSizeLimit limit(4096);
    ExpectTooLarge(Path("n.png"), [&] { WritePng(Path("n.png"), img); });
    ExpectTooLarge(Path("n.exr"), [&] { WriteExr(Path("n.exr"), img); });
    ExpectTooLarge(Path("f.png"), [&] { WriteFalseColorPng(Path("f.png"), img, "intensity"); });
    EXPECT_TRUE(Listing().empty());
}

TEST_F(OutputFileTest, ImagesStagedTogetherAppearTogether) {
    const Image img = Noise(8, 8);
    OutputFiles files;
    WriteExr(files, Path("a.exr"), img);
    WritePng(files, Path("a.png"), img);
    EXPECT_FALSE(std::filesystem::exists(Path("a.exr")));
    files.Commit();
    EXPECT_EQ(ReadImage(Path("a.exr")).data, img.data);
    EXPECT_EQ(ReadImage(Path("a.png")).width, 8);
    EXPECT_EQ(Listing().size(), 2u);
}

}  // namespace
}  // namespace phasor
