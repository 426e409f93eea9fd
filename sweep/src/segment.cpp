#include "latsim/sweep/segment.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "latsim/results/run_files.hpp"

namespace latsim::sweep {

namespace fs = std::filesystem;

namespace {

constexpr char kSegmentMagic[8] = {'L', 'S', 'S', 'E', 'G', '1', '\n', '\0'};
constexpr char kFrameMagic[4] = {'L', 'S', 'R', 'F'};
constexpr size_t kHeaderBytes = 20;
// Level 3 gives 90 % of level 6's size in half its time, on run records.
constexpr int kLevel = 3;

void put32(std::string& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xff);
}
void put64(std::string& out, uint64_t v) {
  for (int i = 0; i < 8; ++i) out += static_cast<char>((v >> (8 * i)) & 0xff);
}
uint32_t get32(const unsigned char* p) {
  return static_cast<uint32_t>(p[0]) | static_cast<uint32_t>(p[1]) << 8 | static_cast<uint32_t>(p[2]) << 16 |
         static_cast<uint32_t>(p[3]) << 24;
}
uint64_t get64(const unsigned char* p) { return static_cast<uint64_t>(get32(p)) | static_cast<uint64_t>(get32(p + 4)) << 32; }

uint32_t crc_of(const unsigned char* data, size_t n) {
  return static_cast<uint32_t>(::crc32(::crc32(0L, Z_NULL, 0), data, static_cast<uInt>(n)));
}

void write_all(int fd, const std::string& bytes, const fs::path& file) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw results::WriteError(file, n < 0 ? errno : EIO);
    done += static_cast<size_t>(n);
  }
}

/// A raw inflater, one per thread, reset for each record.
class Inflater {
 public:
  Inflater() {
    if (inflateInit2(&z_, -MAX_WBITS) != Z_OK) throw std::bad_alloc();
  }
  ~Inflater() { inflateEnd(&z_); }
  Inflater(const Inflater&) = delete;
  Inflater& operator=(const Inflater&) = delete;

  /// The text, whole or (`line_only`) up to its first line break, excluded.
  std::string inflate(const unsigned char* data, size_t n, const std::string& dictionary, bool line_only = false) {
    inflateReset(&z_);
    if (!dictionary.empty() &&
        inflateSetDictionary(&z_, reinterpret_cast<const Bytef*>(dictionary.data()), static_cast<uInt>(dictionary.size())) != Z_OK)
      throw std::runtime_error("store: a record's dictionary was refused");
    // Line by line: a slice at a time, so that a first line stops early.
    constexpr size_t kSlice = 4096;
    std::string out(std::max<size_t>(4 * n, kSlice), '\0');
    z_.next_in = const_cast<Bytef*>(data);
    z_.avail_in = static_cast<uInt>(n);
    size_t produced = 0;
    while (true) {
      const size_t room = std::min(out.size() - produced, line_only ? kSlice : out.size() - produced);
      z_.next_out = reinterpret_cast<Bytef*>(out.data() + produced);
      z_.avail_out = static_cast<uInt>(room);
      const int rc = ::inflate(&z_, line_only ? Z_NO_FLUSH : Z_FINISH);
      const size_t before = produced;
      produced += room - z_.avail_out;
      if (line_only) {
        const size_t eol = out.find('\n', before);
        if (eol < produced) {
          out.resize(eol);
          return out;
        }
      }
      if (rc == Z_STREAM_END) break;
      if (rc != Z_BUF_ERROR && rc != Z_OK) throw std::runtime_error("store: a damaged record (inflate failed)");
      if (z_.avail_in == 0 && z_.avail_out != 0) throw std::runtime_error("store: a record cut short");
      if (produced == out.size()) out.resize(out.size() * 2);
    }
    out.resize(produced);
    return out;
  }

 private:
  z_stream z_{};
};

}  // namespace

std::optional<uint64_t> run_id_bits(const std::string& run_id) {
  if (run_id.size() != 16) return std::nullopt;
  uint64_t v = 0;
  for (char c : run_id) {
    int d;
    if (c >= '0' && c <= '9') d = c - '0';
    else if (c >= 'a' && c <= 'f') d = c - 'a' + 10;
    else return std::nullopt;
    v = v << 4 | static_cast<uint64_t>(d);
  }
  return v;
}

struct SegmentWriter::Deflater {
  z_stream z{};
  Deflater() {
    if (deflateInit2(&z, kLevel, Z_DEFLATED, -MAX_WBITS, 8, Z_DEFAULT_STRATEGY) != Z_OK) throw std::bad_alloc();
  }
  ~Deflater() { deflateEnd(&z); }
};

SegmentWriter::SegmentWriter(fs::path dir, std::string stem)
    : dir_(std::move(dir)), stem_(std::move(stem)), deflater_(std::make_unique<Deflater>()) {}

void SegmentWriter::open_next() {
  file_ = dir_ / (stem_ + "." + std::to_string(generation_++) + ".seg");
  dictionary_.clear();
  fd_ = ::open(file_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0) throw results::WriteError(file_, errno);
  try {
    write_all(fd_, std::string(kSegmentMagic, sizeof kSegmentMagic), file_);
  } catch (...) {
    ::close(fd_);
    fd_ = -1;
    throw;
  }
}

SegmentWriter::~SegmentWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void SegmentWriter::append(const std::string& run_id, std::string_view record) {
  const auto id = run_id_bits(run_id);
  if (!id) throw std::invalid_argument("store: \"" + run_id + "\" is not a run id");
  if (fd_ < 0) open_next();
  z_stream& z = deflater_->z;
  deflateReset(&z);
  if (!dictionary_.empty())
    deflateSetDictionary(&z, reinterpret_cast<const Bytef*>(dictionary_.data()), static_cast<uInt>(dictionary_.size()));
  frame_.assign(kHeaderBytes + deflateBound(&z, static_cast<uLong>(record.size())), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(record.data()));
  z.avail_in = static_cast<uInt>(record.size());
  z.next_out = reinterpret_cast<Bytef*>(frame_.data() + kHeaderBytes);
  z.avail_out = static_cast<uInt>(frame_.size() - kHeaderBytes);
  if (deflate(&z, Z_FINISH) != Z_STREAM_END) throw std::runtime_error("store: deflate failed");
  const size_t payload = frame_.size() - kHeaderBytes - z.avail_out;
  frame_.resize(kHeaderBytes + payload);
  std::string header(kFrameMagic, sizeof kFrameMagic);
  put32(header, static_cast<uint32_t>(payload));
  put32(header, crc_of(reinterpret_cast<const unsigned char*>(frame_.data() + kHeaderBytes), payload));
  put64(header, *id);
  frame_.replace(0, kHeaderBytes, header);
  try {
    write_all(fd_, frame_, file_);
  } catch (...) {
    // Frames after a damaged one are never read: the next record opens a new segment.
    ::close(fd_);
    fd_ = -1;
    throw;
  }
  if (dictionary_.empty()) dictionary_.assign(record.substr(0, record.find('\n')));
}

/// One segment file, mapped, with its first record (whose first line is the others' dictionary).
struct StoreIndex::Segment {
  fs::path file;
  const unsigned char* bytes = nullptr;
  size_t size = 0;
  std::string first;
  std::string dictionary;

  ~Segment() {
    if (bytes) ::munmap(const_cast<unsigned char*>(bytes), size);
  }
};

StoreIndex::StoreIndex(const fs::path& store_dir) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (fs::directory_iterator it(store_dir, ec), end; !ec && it != end; it.increment(ec))
    if (it->path().extension() == ".seg") files.push_back(it->path());
  std::sort(files.begin(), files.end());
  Inflater first_inflater;
  for (const fs::path& file : files) {
    auto seg = std::make_unique<Segment>();
    seg->file = file;
    const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw std::runtime_error(file.string() + ": cannot read the results store: " + std::strerror(errno));
    struct stat st {};
    ::fstat(fd, &st);
    seg->size = static_cast<size_t>(st.st_size);
    if (seg->size > 0) {
      void* map = ::mmap(nullptr, seg->size, PROT_READ, MAP_PRIVATE, fd, 0);
      if (map == MAP_FAILED) {
        ::close(fd);
        throw std::runtime_error(file.string() + ": cannot map the results store: " + std::strerror(errno));
      }
      seg->bytes = static_cast<const unsigned char*>(map);
    }
    ::close(fd);
    if (seg->size < sizeof kSegmentMagic || std::memcmp(seg->bytes, kSegmentMagic, sizeof kSegmentMagic) != 0) {
      damaged_bytes_ += seg->size;  // killed before its magic was whole
      continue;
    }
    const auto index = static_cast<uint32_t>(segments_.size());
    size_t at = sizeof kSegmentMagic;
    while (at + kHeaderBytes <= seg->size) {
      const unsigned char* h = seg->bytes + at;
      const uint32_t length = get32(h + 4);
      if (std::memcmp(h, kFrameMagic, sizeof kFrameMagic) != 0 || length > seg->size - at - kHeaderBytes ||
          crc_of(h + kHeaderBytes, length) != get32(h + 8))
        break;
      const RecordSpot spot{index, at + kHeaderBytes, length};
      if (seg->first.empty()) {
        seg->first = first_inflater.inflate(seg->bytes + spot.offset, length, {});
        seg->dictionary = seg->first.substr(0, seg->first.find('\n'));
      }
      spots_.emplace(get64(h + 12), spot);  // the first record of a run stays
      at += kHeaderBytes + length;
    }
    damaged_bytes_ += seg->size - at;
    segments_.push_back(std::move(seg));
  }
}

StoreIndex::~StoreIndex() = default;

const std::string& StoreIndex::segment_first_record(const RecordSpot& spot) const {
  return segments_[spot.segment]->first;
}

std::optional<RecordSpot> StoreIndex::find(const std::string& run_id) const {
  const auto id = run_id_bits(run_id);
  if (!id) return std::nullopt;
  const auto it = spots_.find(*id);
  if (it == spots_.end()) return std::nullopt;
  return it->second;
}

struct StoreIndex::Reader::Inflating {
  Inflater inflater;
};

StoreIndex::Reader::Reader(const StoreIndex& index) : index_(index), inflating_(std::make_unique<Inflating>()) {}

StoreIndex::Reader::~Reader() = default;

std::string StoreIndex::Reader::read(const RecordSpot& spot) {
  const Segment& seg = *index_.segments_[spot.segment];
  // The first record of a segment is its own text, and the others' dictionary.
  if (spot.offset == sizeof kSegmentMagic + kHeaderBytes) return seg.first;
  return inflating_->inflater.inflate(seg.bytes + spot.offset, spot.length, seg.dictionary);
}

std::string StoreIndex::Reader::read_first_line(const RecordSpot& spot) {
  const Segment& seg = *index_.segments_[spot.segment];
  if (spot.offset == sizeof kSegmentMagic + kHeaderBytes) return seg.dictionary;
  return inflating_->inflater.inflate(seg.bytes + spot.offset, spot.length, seg.dictionary, true);
}

}  // namespace latsim::sweep
