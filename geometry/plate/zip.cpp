#include "geometry/plate/zip.h"

#include <fmt/format.h>
#include <isa-l/crc.h>
#include <isa-l/igzip_lib.h>
#include <libdeflate.h>
#include <sys/mman.h>
#include <zlib.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <limits>
#include <new>
#include <thread>
#include <utility>
#include <vector>

#include "geometry/mesh/file_bytes.h"

namespace tranche::plate {
namespace {

constexpr uint32_t kLocalSig = 0x04034b50, kCentralSig = 0x02014b50, kEndSig = 0x06054b50;
constexpr uint32_t kEnd64Sig = 0x06064b50, kLocator64Sig = 0x07064b50;
constexpr size_t kEndBytes = 22, kLocatorBytes = 20, kEnd64Bytes = 56, kCentralBytes = 46, kLocalBytes = 30;

uint64_t le(std::string_view b, size_t at, int n) {
  uint64_t v = 0;
  for (int i = n - 1; i >= 0; --i) v = v << 8 | static_cast<unsigned char>(b[at + i]);
  return v;
}

void put(std::string& out, uint64_t v, int n) {
  for (int i = 0; i < n; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}

bool iequal(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i])))
      return false;
  return true;
}

// The zip64 extra field (id 1) holds, in order, the fields whose 32-bit value is all ones.
bool apply_zip64(std::string_view extra, ZipEntry& e, bool usize64, bool csize64, bool offset64) {
  for (size_t at = 0; at + 4 <= extra.size();) {
    const uint64_t id = le(extra, at, 2), len = le(extra, at + 2, 2);
    if (at + 4 + len > extra.size()) return false;
    if (id == 1) {
      size_t p = at + 4;
      const size_t end = p + len;
      for (auto [wanted, field] : {std::pair{usize64, &e.size}, {csize64, &e.compressed}, {offset64, &e.local_offset}}) {
        if (!wanted) continue;
        if (p + 8 > end) return false;
        *field = le(extra, p, 8);
        p += 8;
      }
      return true;
    }
    at += 4 + len;
  }
  return !(usize64 || csize64 || offset64);
}

// Why deflate data that libdeflate refused cannot be inflated to `size` bytes, in zlib's words.
std::string inflate_failure(std::string_view in, uint64_t size) {
  z_stream zs{};
  if (inflateInit2(&zs, -MAX_WBITS) != Z_OK) return "zlib could not start";
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data()));
  // zlib counts in 32-bit units: hand it at most 1 GiB of input at a time; the output goes to a
  // scratch buffer, only its length counts.
  constexpr uint64_t kStep = uint64_t{1} << 30;
  std::vector<unsigned char> scratch(1 << 16);
  uint64_t in_left = in.size(), made = 0;
  int rc = Z_OK;
  while (rc == Z_OK && made <= size) {
    if (zs.avail_in == 0 && in_left > 0) {
      zs.avail_in = static_cast<uInt>(std::min(kStep, in_left));
      in_left -= zs.avail_in;
    }
    zs.next_out = scratch.data();
    zs.avail_out = static_cast<uInt>(scratch.size());
    rc = inflate(&zs, Z_NO_FLUSH);  // Z_BUF_ERROR when no progress is possible: the input ran out
    made += scratch.size() - zs.avail_out;
  }
  inflateEnd(&zs);
  if (rc == Z_DATA_ERROR) return "bad deflate data";
  if (made > size) return "the data is longer than the directory says";
  if (rc != Z_STREAM_END) return "the data ends early";
  return "bad deflate data";
}

}  // namespace

bool looks_like_zip(std::string_view bytes) {
  return bytes.size() >= 4 && (le(bytes, 0, 4) == kLocalSig || (bytes.size() == kEndBytes && le(bytes, 0, 4) == kEndSig));
}

Result<ZipArchive> ZipArchive::open(std::string_view b, const std::string& file) {
  const auto damaged = [&](const std::string& what) {
    return Error{file, fmt::format("the ZIP archive is damaged or truncated ({}); download or export it again",
                                   what)};
  };
  if (b.size() < kEndBytes) return damaged("too short for a ZIP archive");
  // The end record: the last signature within the 64 KiB a comment may take.
  size_t end = std::string_view::npos;
  const size_t lowest = b.size() > kEndBytes + 0xffff ? b.size() - kEndBytes - 0xffff : 0;
  for (size_t at = b.size() - kEndBytes + 1; at-- > lowest;) {
    if (le(b, at, 4) == kEndSig && at + kEndBytes + le(b, at + 20, 2) == b.size()) {
      end = at;
      break;
    }
  }
  if (end == std::string_view::npos) return damaged("no end-of-archive record");
  uint64_t count = le(b, end + 10, 2), cd_size = le(b, end + 12, 4), cd_offset = le(b, end + 16, 4);
  if ((count == 0xffff || cd_size == 0xffffffff || cd_offset == 0xffffffff) && end >= kLocatorBytes &&
      le(b, end - kLocatorBytes, 4) == kLocator64Sig) {
    const uint64_t at = le(b, end - kLocatorBytes + 8, 8);
    if (at > b.size() || b.size() - at < kEnd64Bytes || le(b, at, 4) != kEnd64Sig)
      return damaged("bad ZIP64 end record");
    count = le(b, at + 32, 8);
    cd_size = le(b, at + 40, 8);
    cd_offset = le(b, at + 48, 8);
  }
  if (cd_offset > b.size() || cd_size > b.size() - cd_offset) return damaged("the directory lies outside the file");
  if (count > cd_size / kCentralBytes) return damaged("the directory is shorter than its entry count");
  ZipArchive z;
  z.bytes_ = b;
  z.file_ = file;
  z.entries_.reserve(count);
  size_t at = cd_offset;
  const size_t cd_end = cd_offset + cd_size;
  for (uint64_t i = 0; i < count; ++i) {
    if (cd_end - at < kCentralBytes || le(b, at, 4) != kCentralSig) return damaged(fmt::format("entry {}", i + 1));
    const size_t name_len = le(b, at + 28, 2), extra_len = le(b, at + 30, 2), comment_len = le(b, at + 32, 2);
    if (cd_end - at - kCentralBytes < name_len + extra_len + comment_len)
      return damaged(fmt::format("entry {}", i + 1));
    ZipEntry e;
    e.flags = static_cast<uint16_t>(le(b, at + 8, 2));
    e.method = static_cast<uint16_t>(le(b, at + 10, 2));
    e.crc = static_cast<uint32_t>(le(b, at + 16, 4));
    e.compressed = le(b, at + 20, 4);
    e.size = le(b, at + 24, 4);
    e.local_offset = le(b, at + 42, 4);
    e.name = std::string(b.substr(at + kCentralBytes, name_len));
    if (!apply_zip64(b.substr(at + kCentralBytes + name_len, extra_len), e, e.size == 0xffffffff,
                     e.compressed == 0xffffffff, e.local_offset == 0xffffffff))
      return damaged(fmt::format("entry '{}'", e.name));
    while (!e.name.empty() && e.name.front() == '/') e.name.erase(0, 1);
    z.entries_.push_back(std::move(e));
    at += kCentralBytes + name_len + extra_len + comment_len;
  }
  return z;
}

const ZipEntry* ZipArchive::find(std::string_view name) const {
  while (!name.empty() && name.front() == '/') name.remove_prefix(1);
  for (const auto& e : entries_)
    if (iequal(e.name, name)) return &e;
  return nullptr;
}

Result<std::string_view> ZipArchive::data_of(const ZipEntry& e, uint64_t limit) const {
  const std::string where = file_ + ", " + e.name;
  if (e.flags & 1) return Error{where, "the entry is encrypted; save the file again without a password"};
  if (e.method != 0 && e.method != 8)
    return Error{where, fmt::format("compression method {} is not supported (only stored and deflated)", e.method)};
  if (e.size > limit) return Error{where, fmt::format("the entry is too large ({} MB)", e.size >> 20)};
  const auto& b = bytes_;
  if (e.local_offset > b.size() || b.size() - e.local_offset < kLocalBytes || le(b, e.local_offset, 4) != kLocalSig)
    return damaged(e, "no local header");
  const uint64_t data = e.local_offset + kLocalBytes + le(b, e.local_offset + 26, 2) + le(b, e.local_offset + 28, 2);
  if (data > b.size() || e.compressed > b.size() - data) return damaged(e, "the data runs past the end of the file");
  const std::string_view in = b.substr(data, e.compressed);
  // Deflate cannot expand more than 1032 to 1: a larger claim is damage, not a reason to allocate.
  if (e.method == 8 && e.size > 1032 * e.compressed + 64) return damaged(e, "its size is impossible for its data");
  if (e.method == 0 && e.compressed != e.size) return damaged(e, "stored sizes disagree");
  return in;
}

Status ZipArchive::unpack(const ZipEntry& e, std::string_view in, char* out) const {
  if (e.method == 0) {
    if (!in.empty()) std::memcpy(out, in.data(), in.size());
  } else {
    // libdeflate inflates the whole entry in one call, about twice as fast as zlib; when it
    // refuses the data, zlib's streaming inflate says why.
    libdeflate_decompressor* d = libdeflate_alloc_decompressor();
    if (!d) throw std::bad_alloc();
    size_t made = 0;
    const libdeflate_result rc = libdeflate_deflate_decompress_ex(d, in.data(), in.size(), out, e.size, nullptr, &made);
    libdeflate_free_decompressor(d);
    if (rc != LIBDEFLATE_SUCCESS) return damaged(e, inflate_failure(in, e.size));
    if (made != e.size) return damaged(e, "its size disagrees with the directory");
  }
  if (libdeflate_crc32(0, out, e.size) != e.crc) return damaged(e, "CRC mismatch");
  return ok_status();
}

Error ZipArchive::damaged(const ZipEntry& e, const std::string& what) const {
  return Error{file_ + ", " + e.name,
               fmt::format("the ZIP entry is damaged or truncated ({}); download or export the file again", what)};
}

Result<std::string> ZipArchive::read(const ZipEntry& e, uint64_t limit) const {
  auto in = data_of(e, limit);
  if (!in) return in.error();
  std::string out(e.size, '\0');
  if (Status s = unpack(e, *in, out.data()); !s) return s.error();
  return out;
}

Result<ZipBytes> ZipArchive::read_bytes(const ZipEntry& e, uint64_t limit) const {
  auto in = data_of(e, limit);
  if (!in) return in.error();
  ZipBytes out(e.size);
  // Fresh memory is zeroed by the kernel when first written: for a large entry, a second thread
  // has the pages made ready from the end while the inflating (one thread) fills them from the
  // start, so that the zeroing is not on its way.
  struct Helper {  // stopped and joined however unpack() returns, a throw included
    std::thread t;
    std::atomic<bool> stop{false};
    ~Helper() {
      stop = true;
      if (t.joinable()) t.join();
    }
  } ready;
#ifdef MADV_POPULATE_WRITE
  if (e.size >= kPrepared) {
    ready.t = std::thread([base = out.data(), size = e.size, &stop = ready.stop] {
      constexpr size_t kStep = size_t{8} << 20, kHuge = size_t{2} << 20;
      // Down to a quarter of the entry: below, the inflating is there first. A damaged entry
      // stops it early (a size claimed for data that is not there is not made ready).
      for (size_t hi = size; hi > size / 4 && !stop;) {
        const size_t lo = (hi > kStep ? hi - kStep : 0) & ~(kHuge - 1);  // huge-page aligned
        // Only page tables and zeroed pages: the contents the inflating writes are never touched.
        if (madvise(base + lo, hi - lo, MADV_POPULATE_WRITE) != 0) break;  // older kernels: a hint lost
        hi = lo;
      }
    });
  }
#endif
  if (Status s = unpack(e, *in, out.data()); !s) return s.error();
  return out;
}

struct ZipStream::State {
  const ZipArchive* zip = nullptr;
  const ZipEntry* entry = nullptr;
  std::string_view in;    // the entry's data in the archive
  uint64_t in_used = 0;   // of `in`, handed to the inflater (or copied, when stored)
  uint64_t made = 0;      // bytes given out
  uint32_t crc = 0;
  bool done = false;
  inflate_state inflater;  // deflated entries
};

ZipStream::ZipStream(std::unique_ptr<State> s) : s_(std::move(s)) {}
ZipStream::ZipStream(ZipStream&&) noexcept = default;
ZipStream& ZipStream::operator=(ZipStream&&) noexcept = default;
ZipStream::~ZipStream() = default;

Result<ZipStream> ZipArchive::stream(const ZipEntry& e, uint64_t limit) const {
  auto in = data_of(e, limit);
  if (!in) return in.error();
  auto s = std::make_unique<ZipStream::State>();
  s->zip = this;
  s->entry = &e;
  s->in = *in;
  if (e.method == 8) {
    isal_inflate_init(&s->inflater);
    s->inflater.crc_flag = ISAL_DEFLATE;  // no wrapper; the CRC is ours
  }
  return ZipStream(std::move(s));
}

Result<size_t> ZipStream::read(char* out, size_t n) {
  State& s = *s_;
  const ZipEntry& e = *s.entry;
  if (s.done || n == 0) return size_t{0};
  size_t got = 0;
  if (e.method == 0) {
    got = static_cast<size_t>(std::min<uint64_t>(n, s.in.size() - s.in_used));
    if (got) std::memcpy(out, s.in.data() + s.in_used, got);
    s.in_used += got;
  } else {
    // ISA-L counts in 32-bit units: its input is handed over at most 1 GiB at a time.
    constexpr uint64_t kStep = uint64_t{1} << 30;
    inflate_state& z = s.inflater;
    z.next_out = reinterpret_cast<uint8_t*>(out);
    z.avail_out = static_cast<uint32_t>(std::min<size_t>(n, kStep));
    while (z.avail_out > 0 && z.block_state != ISAL_BLOCK_FINISH) {
      if (z.avail_in == 0 && s.in_used < s.in.size()) {
        z.next_in = reinterpret_cast<uint8_t*>(const_cast<char*>(s.in.data() + s.in_used));
        z.avail_in = static_cast<uint32_t>(std::min(kStep, s.in.size() - s.in_used));
        s.in_used += z.avail_in;
      }
      const uint32_t before = z.avail_out;
      const int rc = isal_inflate(&z);
      if (rc < 0) {
        s.done = true;
        return s.zip->damaged(e, inflate_failure(s.in, e.size));
      }
      if (z.avail_out == before && z.avail_in == 0 && s.in_used == s.in.size() && z.block_state != ISAL_BLOCK_FINISH)
        break;  // no input left, and the data has not ended
    }
    got = static_cast<size_t>(reinterpret_cast<char*>(z.next_out) - out);
  }
  if (got > e.size - s.made) {
    s.done = true;
    return s.zip->damaged(e, "the data is longer than the directory says");
  }
  s.crc = crc32_gzip_refl(s.crc, reinterpret_cast<const unsigned char*>(out), got);
  s.made += got;
  if (got > 0) return got;
  // Nothing more: the entry must have ended, at its size, with its CRC.
  s.done = true;
  if (e.method == 8 && s.inflater.block_state != ISAL_BLOCK_FINISH)
    return s.zip->damaged(e, inflate_failure(s.in, e.size));
  if (s.made != e.size) return s.zip->damaged(e, "its size disagrees with the directory");
  if (s.crc != e.crc) return s.zip->damaged(e, "CRC mismatch");
  return size_t{0};
}

ZipBytes::ZipBytes(size_t size) : size_(size) {
  if (size == 0) return;
#ifdef MADV_HUGEPAGE
  if (size >= kMapped) {
    data_ = geo::map_huge(size);  // its first 2 MiB huge pages too (the inflating's chunks: 500 page faults fewer)
    if (!data_) throw std::bad_alloc();
    return;
  }
#endif
  data_ = new char[size];
}

ZipBytes::~ZipBytes() { release(); }

void ZipBytes::release() {
  if (!data_) return;
#ifdef MADV_HUGEPAGE
  if (size_ >= kMapped) {
    munmap(data_, geo::huge_length(size_));
    data_ = nullptr;
    return;
  }
#endif
  delete[] data_;
  data_ = nullptr;
}

ZipBytes::ZipBytes(ZipBytes&& o) noexcept : data_(std::exchange(o.data_, nullptr)), size_(std::exchange(o.size_, 0)) {}

ZipBytes& ZipBytes::operator=(ZipBytes&& o) noexcept {
  if (this != &o) {
    release();
    data_ = std::exchange(o.data_, nullptr);
    size_ = std::exchange(o.size_, 0);
  }
  return *this;
}

std::string write_stored_zip(const std::vector<std::pair<std::string, std::string>>& files) {
  std::string out, directory;
  for (const auto& file : files) {
    const std::string& name = file.first;  // not a structured binding: the lambda below uses it
    const std::string& content = file.second;
    const uint32_t crc = libdeflate_crc32(0, content.data(), content.size());
    const uint64_t offset = out.size();
    auto header = [&](std::string& to, bool central) {
      put(to, central ? kCentralSig : kLocalSig, 4);
      if (central) put(to, 20, 2);  // version made by
      put(to, 20, 2);               // version needed
      put(to, 0, 2);                // flags
      put(to, 0, 2);                // stored
      put(to, 0, 2);                // time
      put(to, 0x21, 2);             // date: 1980-01-01
      put(to, crc, 4);
      put(to, content.size(), 4);
      put(to, content.size(), 4);
      put(to, name.size(), 2);
      put(to, 0, 2);  // extra
      if (central) {
        put(to, 0, 2);  // comment
        put(to, 0, 2);  // disk
        put(to, 0, 2);  // internal attributes
        put(to, 0, 4);  // external attributes
        put(to, offset, 4);
      }
      to += name;
    };
    header(out, false);
    out += content;
    header(directory, true);
  }
  const uint64_t cd_offset = out.size();
  out += directory;
  put(out, kEndSig, 4);
  put(out, 0, 4);  // disk numbers
  put(out, files.size(), 2);
  put(out, files.size(), 2);
  put(out, directory.size(), 4);
  put(out, cd_offset, 4);
  put(out, 0, 2);  // comment
  return out;
}

}  // namespace tranche::plate
