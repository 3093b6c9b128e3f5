#include "meshwave/client/local_state.h"

#include <gtest/gtest.h>

#include <fstream>

#include "client_test_stream.h"
#include "e2e/cli_runner.h"
#include "meshwave/container.h"
#include "meshwave/progression.h"

namespace meshwave::client {
namespace {

using testing::ClientTestStream;
using testing::ReadBytes;
using testing::TempDir;

LocalState SampleState() {
  const auto& s = ClientTestStream();
  const auto order = PacketOrder(s.header, Progression::kRd, 2);
  const Selection sel = SelectPackets(s.header, order, 4000);
  LocalState st;
  st.url = *ParseMeshUrl("http://127.0.0.1:8080/v1/meshes/0123456789ab");
  st.order = Progression::kRd;
  st.max_level = 2;
  st.cursor = sel.ids.size();
  st.budget_bytes = 4000;
  st.container = SerializeContainer(s, sel.ids);
  return st;
}

void WriteBytes(const std::filesystem::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary) << bytes;
}

TEST(LocalStateTest, RoundTripsAndLeavesNoTemporaryFiles) {
  TempDir dir;
  const auto file = dir / "m.mwv";
  const LocalState st = SampleState();
  ASSERT_TRUE(SaveState(file, st).ok());
  auto back = LoadState(file);
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  EXPECT_EQ(back->url.ToString(), st.url.ToString());
  EXPECT_EQ(back->order, st.order);
  EXPECT_EQ(back->max_level, 2);
  EXPECT_EQ(back->cursor, st.cursor);
  EXPECT_EQ(back->budget_bytes, 4000u);
  EXPECT_EQ(back->container, st.container);
  // The state is a plain valid container.
  const std::string bytes = ReadBytes(file);
  EXPECT_TRUE(ParseContainer(bytes).ok());
  int files = 0;
  for (const auto& e :
       std::filesystem::directory_iterator(file.parent_path())) {
    (void)e;
    ++files;
  }
  EXPECT_EQ(files, 2);  // m.mwv and m.mwv.session
}

TEST(LocalStateTest, RefusesACorruptContainer) {
  TempDir dir;
  const auto file = dir / "m.mwv";
  ASSERT_TRUE(SaveState(file, SampleState()).ok());
  const std::string good = ReadBytes(file);
  WriteBytes(file, good.substr(0, good.size() - 10));
  auto cut = LoadState(file);
  ASSERT_FALSE(cut.ok());
  EXPECT_EQ(cut.status().code(), StatusCode::kParseError);
  EXPECT_NE(cut.status().message().find(file.string()), std::string::npos);
  std::string bad = good;
  bad[0] = 'X';
  WriteBytes(file, bad);
  EXPECT_EQ(LoadState(file).status().code(), StatusCode::kParseError);
}

TEST(LocalStateTest, RefusesACorruptOrMismatchedSidecar) {
  TempDir dir;
  const auto file = dir / "m.mwv";
  LocalState st = SampleState();
  ASSERT_TRUE(SaveState(file, st).ok());
  WriteBytes(SidecarPath(file), "\xff\xff\xff garbage");
  EXPECT_EQ(LoadState(file).status().code(), StatusCode::kParseError);

  st.cursor += 1;  // says one packet more than the container holds
  ASSERT_TRUE(SaveState(file, st).ok());
  auto mismatch = LoadState(file);
  ASSERT_FALSE(mismatch.ok());
  EXPECT_NE(mismatch.status().message().find("do not belong together"),
            std::string::npos);

  std::filesystem::remove(SidecarPath(file));
  EXPECT_EQ(LoadState(file).status().code(), StatusCode::kIoError);
}

// The container the packets came from (docs/API.md, "Re-encoded meshes")
// comes back as saved; a sidecar naming something else is refused.
TEST(LocalStateTest, KeepsTheServedContainerAndRefusesAMalformedOne) {
  TempDir dir;
  const auto file = dir / "m.mwv";
  LocalState st = SampleState();
  st.served_container = std::string(64, 'a');
  ASSERT_TRUE(SaveState(file, st).ok());
  auto back = LoadState(file);
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  EXPECT_EQ(back->served_container, st.served_container);

  st.served_container = "not-a-digest";
  ASSERT_TRUE(SaveState(file, st).ok());
  auto bad = LoadState(file);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code(), StatusCode::kParseError);
  EXPECT_NE(bad.status().message().find("served_container is not a container digest"),
            std::string::npos)
      << bad.status().message();
}

}  // namespace
}  // namespace meshwave::client
