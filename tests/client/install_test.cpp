// `cmake --install` to a temporary prefix, then docs/client-example built
// against it with find_package(meshwave) and run: the package is usable
// from outside the source tree, the client links the decoder library and
// not the codec, and the decoder links alone, without protobuf.
#include <gtest/gtest.h>

#include "test_data.h"
#include "e2e/cli_runner.h"

namespace meshwave {
namespace {

using testing::ShellQuote;
using testing::TempDir;

int RunShell(const std::string& cmd, const std::filesystem::path& log) {
  return std::system(
      (cmd + " >>" + ShellQuote(log.string()) + " 2>&1").c_str());
}

TEST(ClientInstallTest, ExampleProjectBuildsAgainstTheInstalledPackage) {
  TempDir dir;
  const auto log = dir / "log.txt";
  const std::string cmake = ShellQuote(testing::CMakeCommand().string());
  const auto prefix = dir / "prefix";
  ASSERT_EQ(RunShell(cmake + " --install " + ShellQuote(testing::BuildDir().string()) +
                    " --prefix " + ShellQuote(prefix.string()),
                log),
            0)
      << testing::ReadBytes(log);
  EXPECT_TRUE(
      std::filesystem::exists(prefix / "include/meshwave/client/session.h"));
  EXPECT_TRUE(std::filesystem::exists(prefix / "include/stream.pb.h"));
  EXPECT_TRUE(std::filesystem::exists(
      prefix / "lib/cmake/meshwave/meshwaveConfig.cmake"));

  const auto build = dir / "example";
  ASSERT_EQ(RunShell(cmake + " -S " + ShellQuote((testing::SourceDir() / "docs/client-example").string()) + " -B " +
                    ShellQuote(build.string()) + " -DCMAKE_BUILD_TYPE=Release" +
                    " -DCMAKE_PREFIX_PATH=" + ShellQuote(prefix.string()),
                log),
            0)
      << testing::ReadBytes(log);
  ASSERT_EQ(RunShell(cmake + " --build " + ShellQuote(build.string()) + " -j2", log),
            0)
      << testing::ReadBytes(log);
  // It runs, and refuses a malformed URL with the library's message.
  const int code = RunShell(
      ShellQuote((build / "fetch_example").string()) + " ftp://x 100 out.ply",
      log);
  EXPECT_EQ(WEXITSTATUS(code), 1);
  EXPECT_NE(testing::ReadBytes(log).find("expected http://, https://, ws:// or wss://"),
            std::string::npos)
      << testing::ReadBytes(log);

  // What each example links (CMake's link line for it).
  const std::string fetch_link =
      testing::ReadBytes(build / "CMakeFiles/fetch_example.dir/link.txt");
  const std::string decode_link =
      testing::ReadBytes(build / "CMakeFiles/decode_example.dir/link.txt");
  EXPECT_NE(fetch_link.find("libmeshwave_decoder.a"), std::string::npos) << fetch_link;
  EXPECT_EQ(fetch_link.find("libmeshwave_codec.a"), std::string::npos) << fetch_link;
  EXPECT_NE(decode_link.find("libmeshwave_decoder.a"), std::string::npos) << decode_link;
  for (const char* other : {"libmeshwave_codec.a", "libmeshwave_proto.a", "protobuf", "boost"}) {
    EXPECT_EQ(decode_link.find(other), std::string::npos) << other << " in " << decode_link;
  }
  // The decoder alone decodes a real stream.
  const auto ply = dir / "decoded.ply";
  ASSERT_EQ(RunShell(ShellQuote((build / "decode_example").string()) + " " +
                         ShellQuote((testing::TestDataDir() / ".." / "fuzz" / "data" /
                                     "tetrahedron_sr2.mwv")
                                        .string()) +
                         " 100000 " + ShellQuote(ply.string()),
                     log),
            0)
      << testing::ReadBytes(log);
  EXPECT_NE(testing::ReadBytes(log).find("34 vertices, 64 faces"), std::string::npos)
      << testing::ReadBytes(log);
  EXPECT_EQ(testing::ReadBytes(ply).rfind("ply\n", 0), 0u);
}

}  // namespace
}  // namespace meshwave
