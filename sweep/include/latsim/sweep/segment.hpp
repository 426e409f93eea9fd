// The results store's files: segments of run records, each written by one
// run thread of one process and read back by every table writer and report.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace latsim::sweep {

/// Appends run records to segment files of its own, DIR/store/<stem>.<n>.seg.
/// A segment is "LSSEG1\n\0" and then frames: a 20-byte header (the magic
/// "LSRF", the payload's length and CRC-32, the run id as 8 bytes) and the
/// record deflated (raw, RFC 1951), the first record of the segment alone and
/// every later one with the first one's first line (its summary) as preset
/// dictionary: a run's record is a fraction of its text, and each can be read
/// by itself. A frame is
/// written with one write(); a frame cut short (the writer was killed) or
/// damaged fails its length or CRC, and a reader stops there. The file is
/// made on the first record; after a failed write (a full disk) the next
/// record starts a new file (n + 1), since nothing after a damaged frame is
/// read. Not thread-safe: one writer per thread.
class SegmentWriter {
 public:
  /// `stem`: unique to this writer among every process (host, pid, thread).
  SegmentWriter(std::filesystem::path dir, std::string stem);
  ~SegmentWriter();
  SegmentWriter(const SegmentWriter&) = delete;
  SegmentWriter& operator=(const SegmentWriter&) = delete;

  /// Appends the record of `run_id` (16 hex digits); throws results::WriteError.
  void append(const std::string& run_id, std::string_view record);
  /// Whether the next record will be the first of a segment (written whole).
  bool starts_segment() const { return fd_ < 0; }

 private:
  void open_next();

  std::filesystem::path dir_;
  std::string stem_;
  int generation_ = 0;
  std::filesystem::path file_;
  int fd_ = -1;
  std::string dictionary_;  // the first record's first line
  struct Deflater;
  std::unique_ptr<Deflater> deflater_;
  std::string frame_;  // reused between records
};

/// Where one record lies.
struct RecordSpot {
  uint32_t segment = 0;
  uint64_t offset = 0;  ///< of its payload in the segment
  uint32_t length = 0;
};

/// Every record in a store directory, by run id, from one pass over the
/// segments' frame headers (the records are inflated only when read). Where
/// a run has two records (two processes ran it, one after the other's claim
/// went stale), the first segment in name order, then the first frame, wins.
class StoreIndex {
 public:
  /// Reads every segment of `store_dir`; segments are mapped, not copied.
  explicit StoreIndex(const std::filesystem::path& store_dir);
  ~StoreIndex();
  StoreIndex(const StoreIndex&) = delete;
  StoreIndex& operator=(const StoreIndex&) = delete;

  std::optional<RecordSpot> find(const std::string& run_id) const;
  size_t size() const { return spots_.size(); }
  /// The first record of the spot's segment (whose scenario the others' patch).
  const std::string& segment_first_record(const RecordSpot& spot) const;

  /// Reads records of an index; one per thread (it keeps its inflater).
  class Reader {
   public:
    explicit Reader(const StoreIndex& index);
    ~Reader();
    Reader(const Reader&) = delete;
    Reader& operator=(const Reader&) = delete;
    /// The record's text.
    std::string read(const RecordSpot& spot);
    /// Its first line alone (the summary but its scenario, what the tables
    /// read), inflated no further than that.
    std::string read_first_line(const RecordSpot& spot);

   private:
    const StoreIndex& index_;
    struct Inflating;
    std::unique_ptr<Inflating> inflating_;
  };
  /// Bytes of frames cut short or damaged at the end of segments (writers killed midway).
  uint64_t damaged_bytes() const { return damaged_bytes_; }

 private:
  struct Segment;
  std::vector<std::unique_ptr<Segment>> segments_;
  std::unordered_map<uint64_t, RecordSpot> spots_;
  uint64_t damaged_bytes_ = 0;
};

/// A run id of 16 hex digits as the 64-bit number it spells; nothing for any other text.
std::optional<uint64_t> run_id_bits(const std::string& run_id);

}  // namespace latsim::sweep
