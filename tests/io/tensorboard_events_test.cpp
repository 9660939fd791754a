// TensorBoard event files: CRC-32C against its published check value, and scalars read back
// by a reader written from the documented formats (tests/common/tfrecord_reader.h).
#include "io/tensorboard_events.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "common/tfrecord_reader.h"
#include "io/temp_folder.h"

namespace glint {
namespace {

TEST(TensorBoardEvents, Crc32cHasItsCheckValue) {
  EXPECT_EQ(crc32c("123456789"), 0xe3069283u);  // the check value of CRC-32C (Castagnoli)
  EXPECT_EQ(crc32c(""), 0u);
  const uint32_t crc = crc32c("123456789");
  EXPECT_EQ(maskedCrc32c("123456789"), ((crc >> 15) | (crc << 17)) + 0xa282ead8u);
}

TEST(TensorBoardEvents, ScalarsReadBackWithTheirStepsAndTags) {
  test::TempFolder folder;
  std::filesystem::path file;
  {
    TensorBoardWriter board(folder.path());
    board.scalar("loss", 1, 0.5f);
    board.scalar("test/diffuse_psnr", 1000, 27.25f);
    board.scalar("loss", 123456789012, -3.0f);
    board.flush();
    file = board.file();
  }
  EXPECT_EQ(file.parent_path(), folder.path());
  EXPECT_EQ(file.filename().string().rfind("events.out.tfevents.", 0), 0u) << file;
  const test::EventFile events = test::readEventFile(file.string());
  EXPECT_TRUE(events.framingValid);
  EXPECT_EQ(events.fileVersion, "brain.Event:2");
  ASSERT_EQ(events.scalars.size(), 3u);
  EXPECT_EQ(events.scalars[0].tag, "loss");
  EXPECT_EQ(events.scalars[0].step, 1);
  EXPECT_EQ(events.scalars[0].value, 0.5f);
  EXPECT_EQ(events.scalars[1].tag, "test/diffuse_psnr");
  EXPECT_EQ(events.scalars[1].step, 1000);
  EXPECT_EQ(events.scalars[1].value, 27.25f);
  EXPECT_EQ(events.scalars[2].step, 123456789012);
  EXPECT_EQ(events.scalars[2].value, -3.0f);
}

}  // namespace
}  // namespace glint
