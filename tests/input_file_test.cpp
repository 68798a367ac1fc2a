// Files a user names and the text chore quotes from them: special files are
// refused before they are read, reads stop at their bound, and every output
// is valid UTF-8 whatever bytes the input held; files chore writes are
// written whole, and only its own dead temporaries are removed (issue 54).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "base/input_file.hpp"
#include "base/json_file.hpp"
#include "base/temp_file.hpp"
#include "base/utf8.hpp"
#include "test_util.hpp"

namespace chore {
namespace {

namespace fs = std::filesystem;

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(InputFile, SpecialFilesAreRefusedBeforeTheyAreOpened) {
  // /dev/zero reports size 0 and never ends; a FIFO blocks its reader until a writer comes.
  EXPECT_EQ(error_of([] { read_text_file("/dev/zero", 1 << 20, "a BDDL file"); }),
            "/dev/zero: not a file (a character device); expected a BDDL file");
  const fs::path dir = test::scratch_dir("input_file_special");
  const fs::path fifo = dir / "activity.bddl";
  fs::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(error_of([&] { read_text_file(fifo.string(), 1 << 20, "a BDDL file"); }),
            fifo.string() + ": not a file (a FIFO); expected a BDDL file");
  EXPECT_EQ(error_of([&] { read_json_file(dir.string()); }),
            dir.string() + ": not a file (a folder); expected a JSON file");
  EXPECT_EQ(error_of([&] { read_text_file((dir / "absent.json").string(), 1 << 20, "a JSON file"); }),
            (dir / "absent.json").string() + ": no such file; expected a JSON file");
}

TEST(InputFile, AReadStopsAtItsBound) {
  const fs::path file = fs::path(test::scratch_dir("input_file_bound")) / "big.csv";
  std::ofstream(file) << std::string(3 << 20, 'x');
  EXPECT_EQ(read_text_file(file.string(), 3 << 20, "a CSV file").size(), size_t{3} << 20);
  EXPECT_EQ(error_of([&] { read_text_file(file.string(), (3 << 20) - 1, "a CSV file"); }),
            file.string() + ": larger than 2 MB, the limit for a CSV file");
}

TEST(Utf8, InvalidBytesAreEscapedAndValidTextIsKept) {
  EXPECT_EQ(valid_utf8("plain ascii"), "plain ascii");
  EXPECT_EQ(valid_utf8("caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x8D\xB4"), "caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x8D\xB4");
  EXPECT_EQ(valid_utf8("a\xFF"
                       "b"),
            "a\\xFFb");                                               // never a lead byte
  EXPECT_EQ(valid_utf8("\xC0\x80"), "\\xC0\\x80");                    // overlong NUL
  EXPECT_EQ(valid_utf8("\xED\xA0\x80"), "\\xED\\xA0\\x80");           // a UTF-16 surrogate
  EXPECT_EQ(valid_utf8("\xF4\x90\x80\x80"), "\\xF4\\x90\\x80\\x80");  // past U+10FFFF
  EXPECT_EQ(valid_utf8("\xE2\x82"), "\\xE2\\x82");                    // cut short at the end
  EXPECT_EQ(valid_utf8(std::string("a\0b", 3)), std::string("a\0b", 3));
}

TEST(Utf8, ErrorsAndJsonTextAreValidUtf8) {
  EXPECT_STREQ(Error("activity '\xFF\xFE.bddl': unknown").what(), "activity '\\xFF\\xFE.bddl': unknown");
  const nlohmann::json value = {{"file", "runs/\xFFseed0"}, {"ok", "caf\xC3\xA9"}, {"n", 3}};
  EXPECT_THROW((void)value.dump(), nlohmann::json::type_error);  // what json_text is for
  EXPECT_EQ(json_text(value), R"({"file":"runs/\\xFFseed0","n":3,"ok":"café"})");
  const nlohmann::json valid = {{"k", {1, 2}}, {"s", "caf\xC3\xA9"}};
  EXPECT_EQ(json_text(valid, 2), valid.dump(2));
}

// A writer's temporary is FINAL.tmp.PID.N; only those of a PID that no
// longer runs are dead, and only those whose FINAL the caller owns go.
TEST(TempFile, OnlyDeadWritersTemporariesOfOwnFilesAreRemoved) {
  const std::string pid = std::to_string(::getpid());
  const fs::path temp = temp_path_for("runs/checkpoint.pt");
  EXPECT_EQ(temp.string().rfind("runs/checkpoint.pt.tmp." + pid + ".", 0), 0u) << temp;
  EXPECT_NE(temp_path_for("runs/checkpoint.pt"), temp) << "two writes of one process share no temporary";

  EXPECT_EQ(dead_writers_final_name("checkpoint.pt.tmp.999999999.0"), "checkpoint.pt");
  EXPECT_EQ(dead_writers_final_name("a.tmp.b.tmp.999999999.12"), "a.tmp.b");
  EXPECT_EQ(dead_writers_final_name("checkpoint.pt.tmp." + pid + ".0"), "") << "a live writer's";
  EXPECT_EQ(dead_writers_final_name("checkpoint.pt.tmp.1.0"), "") << "PID 1 runs (init)";
  for (const char* other :
       {"checkpoint.pt", "checkpoint.pt.tmp.999999999", "checkpoint.pt.tmp.9999999999.0", "checkpoint.pt.tmp.12x.0",
        "checkpoint.pt.tmp..0", ".tmp.999999999.0", "checkpoint.pt.tmp.999999999.0.bak"}) {
    EXPECT_EQ(dead_writers_final_name(other), "") << other;
  }

  const fs::path dir = test::scratch_dir("temp_file");
  for (const std::string& name : std::vector<std::string>{"checkpoint.pt.tmp.999999999.0", "notes.txt.tmp.999999999.0",
                                                          "checkpoint.pt.tmp." + pid + ".3", "checkpoint.pt"}) {
    std::ofstream(dir / name) << "x";
  }
  // A dead writer's scratch folder goes with what is in it (activity
  // coverage's); a link of such a name stays, and what it points to.
  fs::create_directories(dir / "scratch.pt.tmp.999999999.0" / "inner");
  std::ofstream(dir / "scratch.pt.tmp.999999999.0" / "inner" / "result") << "x";
  const fs::path elsewhere = test::scratch_dir("temp_file_elsewhere");
  std::ofstream(elsewhere / "kept") << "x";
  fs::create_directory_symlink(elsewhere, dir / "linked.pt.tmp.999999999.0");
  remove_dead_writers_temps(dir, [](const std::string& final_name) { return final_name.ends_with(".pt"); });
  EXPECT_FALSE(fs::exists(dir / "checkpoint.pt.tmp.999999999.0"));
  EXPECT_TRUE(fs::exists(dir / "notes.txt.tmp.999999999.0")) << "not the caller's";
  EXPECT_TRUE(fs::exists(dir / ("checkpoint.pt.tmp." + pid + ".3"))) << "still being written";
  EXPECT_TRUE(fs::exists(dir / "checkpoint.pt"));
  EXPECT_FALSE(fs::exists(dir / "scratch.pt.tmp.999999999.0"));
  EXPECT_TRUE(fs::is_symlink(dir / "linked.pt.tmp.999999999.0"));
  EXPECT_TRUE(fs::exists(elsewhere / "kept"));
}

}  // namespace
}  // namespace chore
