// The spool on disk and the queue in front of it: order kept across memory
// and disk, nothing dropped, restarts replay only what was not committed,
// damaged files are reported and cut, a second logger is kept out.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <numeric>

#include "simpartner/logger/record_queue.h"
#include "simpartner/logger/spool.h"

namespace simpartner::logger {
namespace {

class SpoolTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("sp_spool_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::unique_ptr<Spool> Open(uint64_t segment_bytes = 1 << 20) {
    return std::make_unique<Spool>(dir_.string(), segment_bytes,
                                   [this](const std::string& s) { notices_.push_back(s); });
  }
  static Record Make(int64_t n, size_t payload = 100) {
    Record r;
    r.kind = RecordKind::kState;
    r.simulation_id = 7;
    r.received_us = 1000 + n;
    r.payload.assign(payload, static_cast<uint8_t>(n));
    r.payload[0] = static_cast<uint8_t>(n & 0xFF);
    r.payload[1] = static_cast<uint8_t>(n >> 8);
    return r;
  }
  static int64_t Number(const Record& r) { return r.received_us - 1000; }
  std::vector<std::filesystem::path> Segments() const {
    std::vector<std::filesystem::path> out;
    for (const auto& e : std::filesystem::directory_iterator(dir_))
      if (e.path().extension() == ".seg") out.push_back(e.path());
    std::sort(out.begin(), out.end());
    return out;
  }

  std::filesystem::path dir_;
  std::vector<std::string> notices_;
};

TEST_F(SpoolTest, AppendsAndReadsInOrderAcrossSegments) {
  auto spool = Open(1000);  // a new segment every ~8 records
  for (int i = 0; i < 50; ++i) spool->Append(Make(i));
  EXPECT_GT(Segments().size(), 4u);
  for (int i = 0; i < 50; ++i) {
    auto e = spool->ReadNext();
    ASSERT_TRUE(e);
    EXPECT_EQ(Number(e->record), i);
    EXPECT_EQ(e->record.payload, Make(i).payload);
    EXPECT_EQ(e->record.kind, RecordKind::kState);
    EXPECT_EQ(e->record.simulation_id, 7);
  }
  EXPECT_FALSE(spool->ReadNext());
  EXPECT_FALSE(spool->HasUnread());
}

TEST_F(SpoolTest, RestartReplaysOnlyWhatWasNotCommitted) {
  {
    auto spool = Open(1000);
    for (int i = 0; i < 30; ++i) spool->Append(Make(i));
    Spool::Position end;
    for (int i = 0; i < 12; ++i) end = spool->ReadNext()->end;
    spool->Commit(end);
    for (int i = 12; i < 20; ++i) spool->ReadNext();  // read, never committed
  }
  auto spool = Open(1000);
  EXPECT_EQ(spool->StoredBytes(), 18u * FrameRecord(Make(0)).size());
  for (int i = 12; i < 30; ++i) {
    auto e = spool->ReadNext();
    ASSERT_TRUE(e) << i;
    EXPECT_EQ(Number(e->record), i);
  }
  EXPECT_FALSE(spool->ReadNext());
}

TEST_F(SpoolTest, FullyCommittedSegmentsAreDeleted) {
  auto spool = Open(1000);
  for (int i = 0; i < 40; ++i) spool->Append(Make(i));
  Spool::Position end;
  while (auto e = spool->ReadNext()) end = e->end;
  spool->Commit(end);
  EXPECT_TRUE(Segments().empty());
  EXPECT_EQ(spool->StoredBytes(), 0u);
  spool->Append(Make(99));  // and appending goes on
  EXPECT_EQ(Number(spool->ReadNext()->record), 99);
}

TEST_F(SpoolTest, CutShortAppendIsCutOffAtRestart) {
  {
    auto spool = Open();
    for (int i = 0; i < 5; ++i) spool->Append(Make(i));
  }
  // A crash in the middle of an append: half a frame at the end.
  const std::vector<uint8_t> frame = FrameRecord(Make(5));
  {
    std::ofstream out(Segments().back(), std::ios::binary | std::ios::app);
    out.write(reinterpret_cast<const char*>(frame.data()), static_cast<std::streamsize>(frame.size() / 2));
  }
  auto spool = Open();
  ASSERT_EQ(notices_.size(), 1u);
  EXPECT_NE(notices_[0].find("damaged tail of " + std::to_string(frame.size() / 2) + " bytes"),
            std::string::npos)
      << notices_[0];
  for (int i = 0; i < 5; ++i) EXPECT_EQ(Number(spool->ReadNext()->record), i);
  EXPECT_FALSE(spool->ReadNext());
  spool->Append(Make(6));
  const auto six = spool->ReadNext();
  ASSERT_TRUE(six) << "the record appended where the cut-off tail was";
  EXPECT_EQ(Number(six->record), 6);
  EXPECT_EQ(spool->damaged_records(), 0u);
}

TEST_F(SpoolTest, DamagedRecordInAnOlderSegmentIsReportedAndSkipped) {
  {
    auto spool = Open(1000);
    for (int i = 0; i < 30; ++i) spool->Append(Make(i));
  }
  // Flip a payload byte of the 2nd record of the first segment.
  const auto first = Segments().front();
  {
    std::fstream f(first, std::ios::binary | std::ios::in | std::ios::out);
    f.seekp(static_cast<std::streamoff>(FrameRecord(Make(0)).size() + 40));
    f.put('\x55');
  }
  auto spool = Open(1000);
  EXPECT_EQ(Number(spool->ReadNext()->record), 0);
  auto next = spool->ReadNext();
  ASSERT_TRUE(next);
  EXPECT_GT(Number(next->record), 1);  // the rest of segment 1 is skipped
  ASSERT_EQ(notices_.size(), 1u);
  EXPECT_NE(notices_[0].find("checksum mismatch"), std::string::npos) << notices_[0];
  EXPECT_NE(notices_[0].find(first.filename().string()), std::string::npos) << notices_[0];
  EXPECT_EQ(spool->damaged_records(), 1u);
}

TEST_F(SpoolTest, SecondOpenOfTheSameDirectoryIsRefused) {
  auto spool = Open();
  try {
    Open();
    FAIL() << "a second spool opened the same directory";
  } catch (const SpoolError& e) {
    EXPECT_NE(std::string(e.what()).find("in use by another simpartner-logger (pid " +
                                         std::to_string(::getpid()) + ")"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(SpoolTest, UnwritableDirectoryIsAnErrorNamingIt) {
  std::filesystem::create_directories(dir_);
  std::ofstream(dir_ / "file") << "x";
  try {
    Spool spool((dir_ / "file" / "spool").string(), 1 << 20, [](const std::string&) {});
    FAIL();
  } catch (const SpoolError& e) {
    EXPECT_NE(std::string(e.what()).find((dir_ / "file" / "spool").string()), std::string::npos)
        << e.what();
  }
}

TEST_F(SpoolTest, QueueSpillsWhenFullAndKeepsTheOrder) {
  auto spool = Open(4000);
  const uint64_t record_bytes = Make(0).ByteSize();
  RecordQueue queue(10 * record_bytes, spool.get());  // room for 10 in memory
  int next_push = 0, next_take = 0;
  // Pushes outrun takes: memory fills, the rest spills, then it catches up.
  for (int round = 0; round < 20; ++round) {
    for (int k = 0; k < 15; ++k) queue.Push(Make(next_push++));
    Batch batch = queue.Take(7, 1 << 30, std::chrono::milliseconds(0));
    for (const Record& r : batch.records) EXPECT_EQ(Number(r), next_take++);
    queue.Commit(batch);
  }
  EXPECT_GT(queue.Stats().spilled_records, 0u);
  EXPECT_LE(queue.Stats().peak_memory_bytes, 10 * record_bytes);
  while (true) {
    Batch batch = queue.Take(13, 1 << 30, std::chrono::milliseconds(0));
    if (batch.empty()) break;
    for (const Record& r : batch.records) EXPECT_EQ(Number(r), next_take++);
    queue.Commit(batch);
  }
  EXPECT_EQ(next_take, next_push);
  EXPECT_TRUE(queue.Drained());
  EXPECT_FALSE(queue.Stats().spilling);
  EXPECT_EQ(queue.Stats().spool_stored_bytes, 0u);
  // Caught up: memory is used again.
  queue.Push(Make(next_push));
  EXPECT_EQ(queue.Stats().memory_records, 1u);
}

TEST_F(SpoolTest, UnwrittenRecordsAreSavedInFrontForTheNextRun) {
  {
    auto spool = Open(4000);
    RecordQueue queue(5 * Make(0).ByteSize(), spool.get());
    for (int i = 0; i < 20; ++i) queue.Push(Make(i));  // 0..4 in memory, 5..19 on disk
    Batch taken = queue.Take(3, 1 << 30, std::chrono::milliseconds(0));  // 0..2 (never written)
    ASSERT_EQ(taken.records.size(), 3u);
    queue.SaveUnwritten(taken);
  }
  auto spool = Open(4000);
  RecordQueue queue(1 << 20, spool.get());
  std::vector<int64_t> order;
  while (true) {
    Batch b = queue.Take(4, 1 << 30, std::chrono::milliseconds(0));
    if (b.empty()) break;
    for (const Record& r : b.records) order.push_back(Number(r));
    queue.Commit(b);
  }
  std::vector<int64_t> expected(20);
  std::iota(expected.begin(), expected.end(), 0);
  EXPECT_EQ(order, expected);
}

TEST_F(SpoolTest, SavedBatchThatCameFromDiskIsNotReplayedTwice) {
  {
    auto spool = Open(4000);
    RecordQueue queue(2 * Make(0).ByteSize(), spool.get());
    for (int i = 0; i < 10; ++i) queue.Push(Make(i));  // 0,1 memory; 2..9 disk
    queue.Commit(queue.Take(2, 1 << 30, std::chrono::milliseconds(0)));  // 0,1 written
    Batch from_disk = queue.Take(3, 1 << 30, std::chrono::milliseconds(0));  // 2,3,4
    ASSERT_TRUE(from_disk.spool_end);
    queue.Push(Make(10));  // still spilling: to disk after 9
    queue.SaveUnwritten(from_disk);
  }
  auto spool = Open(4000);
  std::vector<int64_t> order;
  while (auto e = spool->ReadNext()) order.push_back(Number(e->record));
  EXPECT_EQ(order, (std::vector<int64_t>{2, 3, 4, 5, 6, 7, 8, 9, 10}));
}

}  // namespace
}  // namespace simpartner::logger
