#include "geometry/plate/threemf_meshes.h"

#include <fmt/format.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <new>
#include <type_traits>

#include <sys/mman.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#include <tmmintrin.h>
#endif

#include "geometry/mesh/weld.h"

namespace tranche::plate::threemf {
namespace {

// The placeholder's corners: (id, -7777, 0), (id, -7776, 0), (id, -7777, 1); ids below 2^24,
// which a float holds exactly.
constexpr float kMarkY = -7777.0f;
constexpr uint32_t kMaxId = 1u << 24;

bool space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

bool digit(char c) { return static_cast<unsigned char>(c - '0') < 10; }

// The number std::from_chars reads from [p, end) into `out`, and the end of what it read (nullptr:
// nothing). The forms nearly every writer uses are read here, giving the same value from_chars
// would; every other form goes to from_chars.
// How many of the 8 bytes of `chunk` (in memory order) are decimal digits before the first that is not.
int leading_digits(uint64_t chunk) {
  // A byte is a digit when its high nibble is 3 and its low nibble plus 6 stays below 16; the
  // bytes that are not get a nonzero value, and the first of those is found by its lowest bit.
  const uint64_t not_digit =
      ((chunk & 0xF0F0F0F0F0F0F0F0ull) ^ 0x3030303030303030ull) | (((chunk & 0x0F0F0F0F0F0F0F0Full) + 0x0606060606060606ull) & 0x1010101010101010ull);
  return not_digit ? std::countr_zero(not_digit) / 8 : 8;
}

// The value of the n (1 to 8) digits at the start of `chunk` (eight digits at once: the bytes
// are paired, then the pairs, then the fours).
uint32_t digits_value(uint64_t chunk, int n) {
  uint64_t v = (chunk - 0x3030303030303030ull) << (8 * (8 - n));  // leading zeros in front
  v = (v * 10) + (v >> 8);
  v = (((v & 0x000000FF000000FFull) * (100 + (1000000ull << 32))) +
       (((v >> 16) & 0x000000FF000000FFull) * (1 + (10000ull << 32)))) >>
      32;
  return static_cast<uint32_t>(v);
}

const char* number(const char* p, const char* end, uint32_t& out) {
  if (end - p >= 8) {  // up to 7 digits at once (and what follows them is no digit)
    uint64_t chunk;
    std::memcpy(&chunk, p, 8);
    if constexpr (std::endian::native == std::endian::little) {
      const int n = leading_digits(chunk);
      if (n > 0 && n < 8) {
        out = digits_value(chunk, n);
        return p + n;
      }
    }
  }
  const char* q = p;
  uint64_t v = 0;
  while (q < end && digit(*q) && v <= UINT32_MAX) v = v * 10 + static_cast<unsigned>(*q++ - '0');
  if (q < end && digit(*q)) v = uint64_t{UINT32_MAX} + 1;  // too many digits: out of range
  if (q == p || v > UINT32_MAX) return nullptr;
  out = static_cast<uint32_t>(v);
  return q;
}

// The digits at q appended to m (m * 10^n + their value), q moved past them; their count n. Past
// 19 digits m wraps: the caller looks at the count.
int append_digits(const char*& q, const char* end, uint64_t& m) {
  static constexpr uint64_t kPow10[8] = {1, 10, 100, 1000, 10000, 100000, 1000000, 10000000};
  if constexpr (std::endian::native == std::endian::little) {
    if (end - q >= 8) {
      uint64_t chunk;
      std::memcpy(&chunk, q, 8);
      const int n = leading_digits(chunk);
      if (n < 8) {
        if (n > 0) m = m * kPow10[n] + digits_value(chunk, n);
        q += n;
        return n;
      }
    }
  }
  int n = 0;
  for (; q < end && digit(*q); ++q, ++n) m = m * 10 + static_cast<unsigned>(*q - '0');
  return n;
}

const char* number(const char* p, const char* end, float& out) {
  // [-]digits[.digits] with at most 15 digits: m (exact in a double) times the double nearest
  // 10^-k is the decimal's value to within 2 units in the last place of a double (two roundings,
  // each within half a unit of the binade's). That double rounds to the float the decimal rounds
  // to unless a point halfway between two floats lies within those 2 units of it, which its low
  // 29 bits (of 52) say: they are 1 then zeros there. Such rare values, and every other form, go
  // to std::from_chars, which rounds exactly.
  const char* q = p;
  const bool minus = q < end && *q == '-';
  q += minus;
  uint64_t m = 0;
  int digits = 0, k = 0;
  const int whole = append_digits(q, end, m);
  digits += whole;
  if (whole > 0 && q < end && *q == '.') {
    ++q;
    k = append_digits(q, end, m);
    digits += k;
  }
  static constexpr double kTenth[] = {1e0,  1e-1, 1e-2,  1e-3,  1e-4,  1e-5,  1e-6,  1e-7,
                                      1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14, 1e-15};
  const bool plain = digits > 0 && digits <= 15 && (q == end || (*q != 'e' && *q != 'E' && !digit(*q)));
  if (plain) {
    const double d = static_cast<double>(m) * kTenth[k];
    uint64_t bits;
    std::memcpy(&bits, &d, sizeof bits);
    const float f = static_cast<float>(d);
    constexpr uint64_t kHalf = uint64_t{1} << 28, kLow = (uint64_t{1} << 29) - 1, kNear = 4;
    // (At most 15 digits: a value that is not 0 is at least 10^-15, far above the least normal
    // float, so the float is never subnormal, which would round a second time.)
    if (((bits & kLow) - (kHalf - kNear)) > 2 * kNear) {
      out = minus ? -f : f;
      return q;
    }
  }
  const auto [e, ec] = std::from_chars(p, end, out);
  return ec == std::errc() ? e : nullptr;
}

// The most the scanner may use of the CPU's vector instructions (limit_simd()).
std::atomic<Simd> simd_limit{Simd::kAvx2};

#if defined(__SSE2__)
// Coordinates read with SSSE3 (number_ssse3()).
bool use_ssse3() {
#if defined(__GNUC__)
  static const bool has = __builtin_cpu_supports("ssse3");
  return has && simd_limit.load(std::memory_order_relaxed) >= Simd::kSsse3;
#else
  return false;
#endif
}

// Plain elements read whole with AVX2 (plain_vertices(), plain_triangles()).
bool use_avx2() {
#if defined(__GNUC__)
  static const bool has = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("ssse3");
  return has && simd_limit.load(std::memory_order_relaxed) >= Simd::kAvx2;
#else
  return false;
#endif
}

// number() of the n bytes (1 to 15) of a coordinate at a, which `x` holds (16 bytes loaded from
// a), with SSSE3 (the byte shuffle): the sign and point taken out, the digits converted at once
// (pairs, fours, eights), then as number(); false for the forms it does not read (number() does).
__attribute__((target("ssse3"))) inline bool decimal_ssse3(__m128i x, const char* a, int n, float& out) {
  const unsigned in = (1u << n) - 1;  // the value's bytes
  const int minus = *a == '-';
  const unsigned dots = static_cast<unsigned>(_mm_movemask_epi8(_mm_cmpeq_epi8(x, _mm_set1_epi8('.')))) & in;
  const int point = dots ? std::countr_zero(dots) : n;  // where the point is (n: none)
  const int whole = point - minus;                      // digits before it
  const int digits = n - minus - (dots ? 1 : 0);
  const __m128i d = _mm_sub_epi8(x, _mm_set1_epi8('0'));
  const unsigned is_digit = static_cast<unsigned>(
      _mm_movemask_epi8(_mm_cmpeq_epi8(_mm_subs_epu8(d, _mm_set1_epi8(9)), _mm_setzero_si128())));
  const unsigned need =
      in & ~static_cast<unsigned>(minus) & ~(dots & (0u - dots));  // all but the sign and point
  if (whole <= 0 || digits > 15 || (is_digit & need) != need) return false;
  // Output byte o holds digit t = o - (16 - digits) (from the byte after the sign, skipping the
  // point); those before the first digit are zeros.
  const __m128i t = _mm_add_epi8(_mm_setr_epi8(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15),
                                 _mm_set1_epi8(static_cast<char>(digits - 16)));
  const __m128i after_point = _mm_cmpgt_epi8(t, _mm_set1_epi8(static_cast<char>(whole - 1)));
  const __m128i from = _mm_sub_epi8(_mm_add_epi8(t, _mm_set1_epi8(static_cast<char>(minus))), after_point);
  const __m128i control = _mm_or_si128(from, _mm_cmpgt_epi8(_mm_setzero_si128(), t));  // negative: a zero
  const __m128i v = _mm_shuffle_epi8(d, control);
  const __m128i pairs =
      _mm_maddubs_epi16(v, _mm_setr_epi8(10, 1, 10, 1, 10, 1, 10, 1, 10, 1, 10, 1, 10, 1, 10, 1));
  const __m128i fours = _mm_madd_epi16(pairs, _mm_setr_epi16(100, 1, 100, 1, 100, 1, 100, 1));
  const __m128i packed = _mm_packs_epi32(fours, fours);  // each below 10^4
  const __m128i eights = _mm_madd_epi16(packed, _mm_setr_epi16(10000, 1, 10000, 1, 10000, 1, 10000, 1));
  const uint64_t both = static_cast<uint64_t>(_mm_cvtsi128_si64(eights));
  const uint64_t m = (both & 0xFFFFFFFF) * 100000000 + (both >> 32);
  static constexpr double kTenth[] = {1e0,  1e-1, 1e-2,  1e-3,  1e-4,  1e-5,  1e-6,  1e-7,
                                      1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14, 1e-15};
  const double r = static_cast<double>(static_cast<int64_t>(m)) * kTenth[digits - whole];
  uint64_t bits;
  std::memcpy(&bits, &r, sizeof bits);
  const float f = static_cast<float>(r);
  constexpr uint64_t kHalf = uint64_t{1} << 28, kLow = (uint64_t{1} << 29) - 1, kNear = 4;  // as number()
  // Without branches on the value (its sign), which no predictor guesses; `out` is written either
  // way (number() writes it again when this gives up). No float is subnormal here (number()).
  const bool ok = ((bits & kLow) - (kHalf - kNear)) > 2 * kNear;
  out = std::bit_cast<float>(std::bit_cast<uint32_t>(f) ^ (static_cast<uint32_t>(minus) << 31));
  return ok;
}

// number() of a coordinate followed by its closing quote within 16 bytes, with SSSE3
// (decimal_ssse3()); the same results as number(), which reads every other form.
__attribute__((target("ssse3"))) const char* number_ssse3(const char* a, const char* end, float& out) {
  if (end - a < 16) return number(a, end, out);
  const __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(a));
  const unsigned quotes = static_cast<unsigned>(_mm_movemask_epi8(_mm_cmpeq_epi8(x, _mm_set1_epi8('"'))));
  const int n = quotes ? std::countr_zero(quotes) : 16;  // up to the closing quote
  if (n >= 1 && n <= 15 && decimal_ssse3(x, a, n, out)) return a + n;
  return number(a, end, out);
}

// The elements of a mesh in the form nearly every writer gives them, `<vertex x="1.5" y="-2"
// z="0.25" />` and `<triangle v1="0" v2="1" v3="2" />` (or `/>` right after the last value), each
// read from one look at its 64 bytes with AVX2 (where its quotes and '<' are), then its values
// converted where they are. The element after it is found from the same look (the next '<', only
// spaces before it), so that where an element begins does not wait for the reading of the one
// before (the chain a parse from byte to byte makes), and nothing in the loop branches on a value.
// Any other form, or an element longer than 64 bytes, is left to the scanner's reading attribute
// after attribute, which reads these forms to the same values (tested at every level, limit_simd()).

// Bit i of each says whether byte i of the 64 bytes at p is a '"', a '<'.
struct Block64 {
  uint64_t quote = 0, open = 0;
};

__attribute__((target("avx2"))) inline uint64_t bits64(__m256i lo, __m256i hi) {
  return uint64_t{static_cast<uint32_t>(_mm256_movemask_epi8(lo))} |
         (uint64_t{static_cast<uint32_t>(_mm256_movemask_epi8(hi))} << 32);
}

__attribute__((target("avx2"))) inline Block64 block64(const char* p) {
  const __m256i lo = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
  const __m256i hi = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p + 32));
  const __m256i quote = _mm256_set1_epi8('"'), open = _mm256_set1_epi8('<');
  return {bits64(_mm256_cmpeq_epi8(lo, quote), _mm256_cmpeq_epi8(hi, quote)),
          bits64(_mm256_cmpeq_epi8(lo, open), _mm256_cmpeq_epi8(hi, open))};
}

// Bit i: byte i of the 16 at p is one of XML's four spaces (the byte its low nibble picks from
// `spaces`; bytes from 0x80 pick 0, which they are not).
__attribute__((target("avx2"))) inline unsigned spaces16(const char* p) {
  const __m128i spaces = _mm_setr_epi8(' ', 0, 0, 0, 0, 0, 0, 0, 0, '\t', '\n', 0, 0, '\r', 0, 0);
  const __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
  return static_cast<unsigned>(_mm_movemask_epi8(_mm_cmpeq_epi8(_mm_shuffle_epi8(spaces, x), x)));
}

// Up to 8 bytes of a literal from `from`, as a load gives them (little-endian, as x86 is).
template <size_t N>
constexpr uint64_t bytes_of(const char (&lit)[N], size_t from = 0) {
  uint64_t v = 0;
  for (size_t i = from; i < N - 1 && i < from + 8; ++i)
    v |= uint64_t{static_cast<uint8_t>(lit[i])} << (8 * (i - from));
  return v;
}

inline uint64_t load8(const char* p) {
  uint64_t v;
  std::memcpy(&v, p, 8);
  return v;
}

// The five quotes after the first one of the block's quotes `q`, at `at`; false when there are
// fewer than five in the 64 bytes.
inline bool five_quotes(uint64_t q, int (&at)[5]) {
  q &= q - 1;  // the first one (the opening quote of the first value) is the head's
  for (int& a : at) {
    if (!q) return false;
    a = std::countr_zero(q);
    q &= q - 1;
  }
  return true;
}

// Where an element whose last value closes at quote q ends: past `"/>` or `" />`; 0: neither.
inline int tag_end(const char* p, int q) {
  constexpr uint64_t kShort = bytes_of("\"/>"), kLong = bytes_of("\" />");
  const uint64_t w = load8(p + q);
  if ((w & 0xFFFFFF) == kShort) return q + 3;
  if ((w & 0xFFFFFFFF) == kLong) return q + 4;
  return 0;
}

// Whether only spaces, at most 16, lie between an element's end e and the block's next '<' at
// `next` (the element's own is at 0, and it holds no other).
__attribute__((target("avx2"))) inline bool spaces_between(const char* p, int e, int next) {
  if (next >= 64 || next - e > 16) return false;
  const unsigned gap = (1u << (next - e)) - 1;
  return (spaces16(p + e) & gap) == gap;
}

// Past an element read whole (its end at p + e, the next element's '<' at p + next): on to the
// next when only spaces lie between (true); otherwise to the element's end, whose spaces the caller
// skips, and the batch ends (false).
__attribute__((target("avx2"))) inline bool step_to_next(const char*& p, int e, int next) {
  if (!spaces_between(p, e, next)) {
    p += e;
    return false;
  }
  p += next;
  return true;
}

// The fast reading needs this many bytes from an element's start: its 64, and the 16 a value or
// the spaces after it are loaded with.
constexpr ptrdiff_t kPlainBytes = 96;

// Elements are read in batches, appended to the caller's vector after each: no call within the
// loop that reads them.
constexpr int kBatch = 256;

// The values of `count` indices (rounded up to a multiple of 4; the values past `count` are
// read too) of at most 8 digits each: the 8 bytes at each value's start in `chunks`, shifted left
// by `shifts` bits (8 for each byte past its n digits), four at a time with AVX2; the values go
// to `out`, 4 bytes each. The index of the first value that is not all decimal digits, or `count`.
__attribute__((target("avx2"))) int indices_avx2(const uint64_t* chunks, const uint64_t* shifts, int count,
                                                 char* out) {
  const __m256i zero = _mm256_setzero_si256();
  for (int i = 0; i < count; i += 4) {
    const __m256i c = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(chunks + i));
    const __m256i s = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(shifts + i));
    // Each lane: its digits' values at the top, most significant first, zeros before them.
    const __m256i d = _mm256_sllv_epi64(_mm256_sub_epi8(c, _mm256_set1_epi8('0')), s);
    const unsigned ok = static_cast<unsigned>(
        _mm256_movemask_epi8(_mm256_cmpeq_epi8(_mm256_subs_epu8(d, _mm256_set1_epi8(9)), zero)));
    if (ok != 0xFFFFFFFFu) return std::min(count, i + std::countr_zero(~ok) / 8);
    const __m256i pairs = _mm256_maddubs_epi16(d, _mm256_set1_epi16(0x010A));       // 10a + b
    const __m256i fours = _mm256_madd_epi16(pairs, _mm256_set1_epi32(0x00010064));  // 100a + b
    // The lane's first four digits times 10^4 plus its last four.
    const __m256i eights =
        _mm256_add_epi64(_mm256_mul_epu32(fours, _mm256_set1_epi64x(10000)), _mm256_srli_epi64(fours, 32));
    const __m256i packed = _mm256_permutevar8x32_epi32(eights, _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 4 * i), _mm256_castsi256_si128(packed));
  }
  return count;
}

// Triangles in the plain form from p on, begun before `limit`, with kPlainBytes before `end`: their
// indices appended to `out`; where the first element not read begins (or the spaces before it).
// A batch of elements is found first, each value's bytes noted; then their values are read at
// once (indices_avx2()), and the batch ends before the first element holding a value that is no
// number.
__attribute__((target("avx2"))) const char* plain_triangles(const char* p, const char* limit, const char* end,
                                                            std::vector<std::array<uint32_t, 3>>& out) {
  static constexpr char kHead[] = "<triangle v1=\"";  // 14 bytes: 0-7 and 6-13
  constexpr uint64_t head0 = bytes_of(kHead), head1 = bytes_of(kHead, 6);
  constexpr uint64_t kSix = (uint64_t{1} << 48) - 1;
  constexpr uint64_t v2 = bytes_of("\" v2=\"") & kSix, v3 = bytes_of("\" v3=\"") & kSix;
  static_assert(sizeof(std::array<uint32_t, 3>) == 12);
  constexpr int kValues = 3 * kBatch + 4;  // read four at a time
  uint64_t chunks[kValues], shifts[kValues];
  const char* starts[kBatch];
  std::array<uint32_t, 3> batch[kBatch + 2];
  for (bool more = true; more;) {
    int n = 0;
    for (; n < kBatch; ++n) {
      more = false;
      if (p >= limit || end - p < kPlainBytes || load8(p) != head0 || load8(p + 6) != head1) break;
      const Block64 b = block64(p);
      // Where the next element begins is found first, so that reading this one is not waited for
      // (checked below: only spaces before it).
      const int next = std::countr_zero(b.open & (b.open - 1));
      int q[5];  // the closing quote of v1, the opening and closing of v2 and v3
      if (!five_quotes(b.quote, q)) break;
      const int n1 = q[0] - 14, n2 = q[2] - q[1] - 1, n3 = q[4] - q[3] - 1;
      if (q[1] != q[0] + 5 || q[3] != q[2] + 5 || n1 < 1 || n1 > 8 || n2 < 1 || n2 > 8 || n3 < 1 || n3 > 8 ||
          (load8(p + q[0]) & kSix) != v2 || (load8(p + q[2]) & kSix) != v3)
        break;
      const int e = tag_end(p, q[4]);
      if (!e) break;
      starts[n] = p;
      chunks[3 * n] = load8(p + 14);
      chunks[3 * n + 1] = load8(p + q[1] + 1);
      chunks[3 * n + 2] = load8(p + q[3] + 1);
      shifts[3 * n] = 8 * (8 - n1);
      shifts[3 * n + 1] = 8 * (8 - n2);
      shifts[3 * n + 2] = 8 * (8 - n3);
      if (!(more = step_to_next(p, e, next))) {
        ++n;
        break;
      }
    }
    for (int i = 3 * n; i < 3 * n + 4; ++i) {  // a whole last four: zeros
      chunks[i] = 0x3030303030303030ull;
      shifts[i] = 0;
    }
    const int first_bad = indices_avx2(chunks, shifts, 3 * n, reinterpret_cast<char*>(batch)) / 3;
    if (first_bad < n) {  // that element is read attribute after attribute (which says what is wrong)
      n = first_bad;
      p = starts[first_bad];
      more = false;
    }
    out.insert(out.end(), batch, batch + n);
  }
  return p;
}

// The value of a coordinate of n bytes at a, as number() reads it; false when it does not read to
// its closing quote, or is no finite number.
__attribute__((target("ssse3"))) inline bool plain_coordinate(const char* a, int n, const char* end,
                                                              float& out) {
  if (n >= 1 && n <= 15 && decimal_ssse3(_mm_loadu_si128(reinterpret_cast<const __m128i*>(a)), a, n, out))
    return true;
  return number(a, end, out) == a + n && std::isfinite(out);
}

// Vertices in the plain form from p on, as plain_triangles(): x, y, z appended to `out`.
__attribute__((target("avx2"))) const char* plain_vertices(const char* p, const char* limit, const char* end,
                                                           std::vector<float>& out) {
  static constexpr char kHead[] = "<vertex x=\"";  // 11 bytes: 0-7 and 3-10
  constexpr uint64_t head0 = bytes_of(kHead), head1 = bytes_of(kHead, 3);
  constexpr uint64_t kFour = (uint64_t{1} << 32) - 1;
  constexpr uint64_t y = bytes_of("\" y=\"") & kFour, z = bytes_of("\" z=\"") & kFour;
  float batch[kBatch][3];
  for (bool more = true; more;) {
    int n = 0;
    for (; n < kBatch; ++n) {
      more = false;
      if (p >= limit || end - p < kPlainBytes || load8(p) != head0 || load8(p + 3) != head1) break;
      const Block64 b = block64(p);
      const int next = std::countr_zero(b.open & (b.open - 1));  // as plain_triangles()
      int q[5];
      if (!five_quotes(b.quote, q)) break;
      if (q[1] != q[0] + 4 || q[3] != q[2] + 4 || (load8(p + q[0]) & kFour) != y ||
          (load8(p + q[2]) & kFour) != z)
        break;
      const int e = tag_end(p, q[4]);
      if (!e || !plain_coordinate(p + 11, q[0] - 11, end, batch[n][0]) ||
          !plain_coordinate(p + q[1] + 1, q[2] - q[1] - 1, end, batch[n][1]) ||
          !plain_coordinate(p + q[3] + 1, q[4] - q[3] - 1, end, batch[n][2]))
        break;
      if (!(more = step_to_next(p, e, next))) {
        ++n;
        break;
      }
    }
    out.insert(out.end(), &batch[0][0], &batch[0][0] + 3 * n);
  }
  return p;
}

#endif

template <class T>
bool parse(std::string_view v, T& out) {
  return number(v.data(), v.data() + v.size(), out) == v.data() + v.size();
}

// A cursor over the XML text that reads the few forms a plain mesh is written in.
class Scanner {
 public:
  Scanner(std::string_view s, size_t at) : s_(s), i_(at) {
#if defined(__SSE2__)
    simd_ = use_ssse3();
    plain_ = use_avx2();
#endif
  }
  size_t pos() const { return i_; }
  void skip_space() {
    while (i_ < s_.size() && space(s_[i_])) ++i_;
  }
  // Whether the text at the cursor is `lit` (a literal: its length is known when compiling).
  template <size_t N>
  bool at(const char (&lit)[N], size_t from) const {
    return s_.size() - from >= N - 1 && std::memcmp(s_.data() + from, lit, N - 1) == 0;
  }
  template <size_t N>
  bool eat(const char (&lit)[N]) {
    if (!at(lit, i_)) return false;
    i_ += N - 1;
    return true;
  }
  // `<name` followed by a space, '>' or '/': consumed.
  template <size_t N>
  bool open(const char (&name)[N]) {
    const size_t after = i_ + N;  // '<' and the name
    if (after >= s_.size() || s_[i_] != '<' || !at(name, i_ + 1)) return false;
    const char c = s_[after];
    if (!space(c) && c != '>' && c != '/') return false;
    i_ = after;
    return true;
  }
  // Calls f(name, value) for each attribute of the tag (false from f: unreadable); then whether
  // the tag closed itself (`/>`), or nothing when the tag is not read to its end.
  template <class F>
  std::optional<bool> attributes(F f) {
    for (;;) {
      skip_space();
      if (i_ >= s_.size()) return std::nullopt;
      if (s_[i_] == '>') {
        ++i_;
        return false;
      }
      if (s_[i_] == '/') return eat("/>") ? std::optional<bool>(true) : std::nullopt;
      size_t n = i_;
      while (n < s_.size() && !space(s_[n]) && s_[n] != '=' && s_[n] != '>' && s_[n] != '/') ++n;
      const std::string_view name = s_.substr(i_, n - i_);
      i_ = n;
      skip_space();
      if (!eat("=")) return std::nullopt;
      skip_space();
      if (i_ >= s_.size() || (s_[i_] != '"' && s_[i_] != '\'')) return std::nullopt;
      const size_t end = s_.find(s_[i_], i_ + 1);
      if (end == std::string_view::npos || !f(name, s_.substr(i_ + 1, end - i_ - 1))) return std::nullopt;
      i_ = end + 1;
    }
  }
  // The fast way through the form most writers use, `<vertex x="1" y="2" z="3"/>` or `<triangle
  // v1="0" v2="1" v3="2" />` (`names` holds the three attributes' ` name="` in order): the values,
  // and the cursor past the tag; false (the cursor unmoved) for any other form.
  template <class T, size_t NT, size_t NA>
  bool three(const char (&tag)[NT], const char (&names)[3][NA], T (&out)[3]) {
    if (!at(tag, i_)) return false;
    size_t i = i_ + NT - 1;
    const char* end = s_.data() + s_.size();
    for (int k = 0; k < 3; ++k) {
      if (!at(names[k], i)) return false;
      i += NA - 1;
      const char* p = read_number(s_.data() + i, end, out[k]);
      if (!p || p == end || *p != '"') return false;
      i = static_cast<size_t>(p - s_.data()) + 1;
    }
    while (i < s_.size() && space(s_[i])) ++i;
    if (!at("/>", i)) return false;
    i_ = i + 2;
    return true;
  }
  // number(), coordinates with SSSE3 where the CPU has it (number_ssse3()).
  const char* read_number(const char* p, const char* end, uint32_t& out) const { return number(p, end, out); }
  const char* read_number(const char* p, const char* end, float& out) const {
#if defined(__SSE2__)
    if (simd_) return number_ssse3(p, end, out);
#endif
    return number(p, end, out);
  }
  // The plain elements at the cursor read at once (plain_vertices(), plain_triangles()), each
  // begun before `limit`: whether there was one.
  template <class T>
  bool plain(std::vector<T>& out, size_t limit) {
#if defined(__SSE2__)
    if (!plain_) return false;
    const char* const b = s_.data();
    const char* const lim = b + std::min(limit, s_.size());
    const char* p;
    if constexpr (std::is_same_v<T, float>)
      p = plain_vertices(b + i_, lim, b + s_.size(), out);
    else
      p = plain_triangles(b + i_, lim, b + s_.size(), out);
    const bool any = p != b + i_;
    i_ = static_cast<size_t>(p - b);
    return any;
#else
    (void)out;
    (void)limit;
    return false;
#endif
  }
  // `<name ...>` (not closed by itself), its attributes ignored.
  template <size_t N>
  bool start(const char (&name)[N]) {
    if (!open(name)) return false;
    const auto closed = attributes([](std::string_view, std::string_view) { return true; });
    return closed && !*closed;
  }

 private:
  std::string_view s_;
  size_t i_;
  [[maybe_unused]] bool simd_ = false;   // read_number() with SSSE3
  [[maybe_unused]] bool plain_ = false;  // plain() with AVX2
};

// How reading a run of elements ended: at its closing tag, at an element it does not read, or
// with the cursor at or past the limit it was given (a streamed text's window: read on after more
// text has come).
enum class Run { kDone, kFailed, kMore, kBad };

// A value that no reader takes as a number (kBad): where it is (at its opening quote) and what.
struct Bad {
  size_t at = std::string_view::npos;
  std::string what;  // `vertex 3 has the coordinate x="abc"` (counted from 0, as the indices)
};

// Whether `v` is written as the 3MF specification writes a number (ST_Number; an index: digits),
// with an optional sign and the spaces XML allows around it, or holds a character reference (which
// lib3mf judges): else no reader takes it as one. Only the values the scanner did not read are
// asked.
bool number_like(std::string_view v, bool index) {
  if (v.find('&') != std::string_view::npos) return true;
  while (!v.empty() && space(v.front())) v.remove_prefix(1);
  while (!v.empty() && space(v.back())) v.remove_suffix(1);
  size_t i = 0;
  const auto digits = [&] {
    const size_t from = i;
    while (i < v.size() && digit(v[i])) ++i;
    return i > from;
  };
  if (i < v.size() && (v[i] == '+' || v[i] == '-')) ++i;
  if (index) return digits() && i == v.size();
  const bool whole = digits();
  bool fraction = false;
  if (i < v.size() && v[i] == '.') {
    ++i;
    fraction = digits();
  }
  if (!whole && !fraction) return false;
  if (i < v.size() && (v[i] == 'e' || v[i] == 'E')) {
    ++i;
    if (i < v.size() && (v[i] == '+' || v[i] == '-')) ++i;
    if (!digits()) return false;
  }
  return i == v.size();
}

// `<vertex x=".." y=".." z=".."/>` elements up to `</vertices>`; an element is begun only before
// `limit`.
Run vertices(Scanner& sc, std::vector<float>& out, size_t limit, Bad& bad) {
  for (;;) {
    if (sc.pos() >= limit) return Run::kMore;
    sc.skip_space();
    if (sc.plain(out, limit)) continue;
    if (sc.eat("</vertices>")) return Run::kDone;
    static constexpr char kXyz[3][5] = {" x=\"", " y=\"", " z=\""};
    float xyz[3];
    if (sc.three("<vertex", kXyz, xyz)) {
      if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2])) return Run::kFailed;
      out.insert(out.end(), xyz, xyz + 3);
      continue;
    }
    if (!sc.open("vertex")) return Run::kFailed;
    int got = 0;
    const auto closed = sc.attributes([&](std::string_view name, std::string_view value) {
      if (name.size() != 1 || name[0] < 'x' || name[0] > 'z') return true;
      got |= 1 << (name[0] - 'x');
      if (parse(value, xyz[name[0] - 'x']) && std::isfinite(xyz[name[0] - 'x'])) return true;
      if (!number_like(value, false))
        bad.what = fmt::format("vertex {} has the coordinate {}=\"{}\"", out.size() / 3, name, value.substr(0, 40));
      return false;
    });
    if (!bad.what.empty()) {
      bad.at = sc.pos();
      return Run::kBad;
    }
    if (!closed || !*closed || got != 7) return Run::kFailed;
    out.insert(out.end(), xyz, xyz + 3);
  }
}

// `<triangle v1=".." v2=".." v3=".." .../>` elements up to `</triangles>` (properties ignored); an
// element is begun only before `limit`.
Run triangles(Scanner& sc, std::vector<std::array<uint32_t, 3>>& out, size_t limit, Bad& bad) {
  for (;;) {
    if (sc.pos() >= limit) return Run::kMore;
    sc.skip_space();
    if (sc.plain(out, limit)) continue;
    if (sc.eat("</triangles>")) return Run::kDone;
    static constexpr char kV123[3][6] = {" v1=\"", " v2=\"", " v3=\""};
    uint32_t v[3];
    if (sc.three("<triangle", kV123, v)) {
      out.push_back({v[0], v[1], v[2]});
      continue;
    }
    if (!sc.open("triangle")) return Run::kFailed;
    int got = 0;
    const auto closed = sc.attributes([&](std::string_view name, std::string_view value) {
      if (name.size() != 2 || name[0] != 'v' || name[1] < '1' || name[1] > '3') return true;
      got |= 1 << (name[1] - '1');
      if (parse(value, v[name[1] - '1'])) return true;
      if (!number_like(value, true))
        bad.what = fmt::format("triangle {} has the vertex index {}=\"{}\"", out.size(), name, value.substr(0, 40));
      return false;
    });
    if (!bad.what.empty()) {
      bad.at = sc.pos();
      return Run::kBad;
    }
    if (!closed || !*closed || got != 7) return Run::kFailed;
    out.push_back({v[0], v[1], v[2]});
  }
}

// Whether a mesh read to its end is one to take: it has triangles, and their indices are in range
// (else lib3mf says what is wrong).
// (`nv` vertices read.)
bool complete(const std::vector<std::array<uint32_t, 3>>& triangles, size_t nv) {
  if (triangles.empty()) return false;
  uint32_t most = 0;
  for (const auto& t : triangles) most = std::max({most, t[0], t[1], t[2]});
  return most < nv;
}

// A plain `<mesh>` at the cursor, read to its end, in the welder's order; nothing for any other
// form, or a mesh lib3mf would refuse (a coordinate that is not a finite number, a vertex index
// out of range); `bad` says where a value is no number at all.
std::optional<MeshData> mesh(Scanner& sc, Bad& bad) {
  MeshData m;
  std::vector<float> read;
  if (!sc.start("mesh")) return std::nullopt;
  sc.skip_space();
  constexpr size_t kWhole = std::string_view::npos;  // no limit: the text is all there
  if (!sc.start("vertices") || vertices(sc, read, kWhole, bad) != Run::kDone) return std::nullopt;
  sc.skip_space();
  if (!sc.start("triangles") || triangles(sc, m.triangles, kWhole, bad) != Run::kDone) return std::nullopt;
  sc.skip_space();
  if (!sc.eat("</mesh>") || !complete(m.triangles, read.size() / 3)) return std::nullopt;
  geo::WeldScratch scratch;
  m.degenerate = geo::order_by_first_use(read.data(), read.size() / 3, m.triangles, m.vertices, scratch);
  m.ordered = true;
  return m;
}

// The attributes of an <object> tag (the scanner just past its name): whether the tag closes
// itself (attributes()'s answer) and its id, when it has a valid one; nullopt when the tag does
// not end in the text.
struct ObjectTag {
  bool self_closed = false;
  std::optional<uint32_t> id;
};
std::optional<ObjectTag> object_tag(Scanner& sc) {
  ObjectTag tag;
  const auto closed = sc.attributes([&](std::string_view name, std::string_view value) {
    uint32_t v = 0;
    if (name == "id" && parse(value, v)) tag.id = v;
    return true;
  });
  if (!closed) return std::nullopt;
  tag.self_closed = *closed;
  return tag;
}

std::string placeholder(uint32_t id) {
  return fmt::format(
      "<mesh><vertices><vertex x=\"{0}\" y=\"{1}\" z=\"0\"/><vertex x=\"{0}\" y=\"{2}\" z=\"0\"/><vertex x=\"{0}\" "
      "y=\"{1}\" z=\"1\"/></vertices><triangles><triangle v1=\"0\" v2=\"1\" v3=\"2\"/></triangles></mesh>",
      id, kMarkY, kMarkY + 1);
}

// Where "<object" is in `xml`, in order. Searched for by its 'j', which the elements of a mesh
// never hold (memchr is fast where its byte is rare), in parallel slices of the text.
std::vector<size_t> find_objects(std::string_view xml) {
  constexpr size_t kSlice = size_t{8} << 20;
  const size_t slices = (xml.size() + kSlice - 1) / kSlice;
  std::vector<std::vector<size_t>> found(slices);
  tbb::parallel_for(size_t{0}, slices, [&](size_t i) {
    const char* begin = xml.data();
    const char* p = begin + i * kSlice;
    const char* end = begin + std::min(xml.size(), (i + 1) * kSlice);
    const char* text_end = begin + xml.size();
    while ((p = static_cast<const char*>(std::memchr(p, 'j', static_cast<size_t>(end - p)))) != nullptr) {
      // "<ob" before the 'j', "ect" after it
      if (p - begin >= 3 && text_end - p >= 4 && std::memcmp(p - 3, "<object", 7) == 0)
        found[i].push_back(static_cast<size_t>(p - 3 - begin));
      ++p;
    }
  });
  std::vector<size_t> out;
  for (const auto& f : found) out.insert(out.end(), f.begin(), f.end());
  return out;
}

// Whether `at` lies in a comment of `xml` (which lib3mf skips).
bool in_comment(std::string_view xml, size_t at) {
  const size_t open = xml.rfind("<!--", at);
  if (open == std::string_view::npos) return false;
  const size_t close = xml.find("-->", open + 4);
  return close == std::string_view::npos || close > at;
}

}  // namespace

SplitModel split_meshes(std::string_view xml) {
  SplitModel out;
  // Read as one pass would: an object after another, from `at`; a mesh read whole moves `at` past
  // it, else the search goes on after the object's tag. A mesh is replaced only where it was read
  // whole, element after element: a comment or CDATA section cannot begin or end inside it (the
  // mesh would not read), so a mesh in a comment is replaced in the comment, which lib3mf skips,
  // and an object of the same id after it is left to lib3mf (ids are taken once).
  //
  // The meshes are read in parallel: the next few objects' tags are read ahead as if no mesh
  // before them read (a mesh that does read may hold them, in attribute values: they are then
  // passed over), their meshes are read at once, and the objects are then taken in order.
  struct Ahead {
    size_t at = 0;                  // of "<object"
    size_t after = 0;               // past its tag; 0: no object tag there
    bool broken = false;            // the tag is not read to its end: the rest is lib3mf's
    std::optional<uint32_t> id;     // when the tag is not closed by itself
    size_t start = 0, end = 0;      // of the mesh, if it reads
    std::optional<MeshData> mesh;
    Bad bad;                        // a value in it that is no number
  };
  constexpr size_t kAhead = 16;
  const std::vector<size_t> objects = find_objects(xml);
  const auto next_object = [&](size_t from) {
    const auto it = std::lower_bound(objects.begin(), objects.end(), from);
    return it == objects.end() ? std::string_view::npos : *it;
  };
  size_t copied = 0;  // xml[0, copied) is in out.model
  size_t at = next_object(0);
  bool done = false;
  std::vector<Ahead> batch;
  while (!done && at != std::string_view::npos) {
    batch.clear();
    for (size_t p = at; batch.size() < kAhead;) {
      p = next_object(p);
      if (p == std::string_view::npos) break;
      Ahead& a = batch.emplace_back();
      a.at = p;
      Scanner sc(xml, p);
      if (!sc.open("object")) {
        p += 7;
        continue;
      }
      const auto tag = object_tag(sc);
      if (!tag) {
        a.broken = true;
        break;
      }
      a.after = p = sc.pos();
      if (!tag->self_closed) a.id = tag->id;
    }
    tbb::parallel_for(size_t{0}, batch.size(), [&](size_t i) {
      Ahead& a = batch[i];
      if (!a.id || *a.id >= kMaxId) return;
      Scanner sc(xml, a.after);
      sc.skip_space();
      a.start = sc.pos();
      a.mesh = mesh(sc, a.bad);
      a.end = sc.pos();
    });
    for (Ahead& a : batch) {
      if (a.at < at) continue;  // inside a mesh read
      if (a.broken) {
        done = true;
        break;
      }
      if (!a.after) {
        at = a.at + 7;
        continue;
      }
      at = a.after;
      if (a.id && *a.id < kMaxId && !out.meshes.count(*a.id) && !a.mesh && a.bad.at != std::string_view::npos &&
          out.bad.empty() && !in_comment(xml, a.bad.at))
        out.bad = fmt::format("line {}, object {}: {}, which is not a number",
                              1 + std::count(xml.begin(), xml.begin() + static_cast<ptrdiff_t>(a.bad.at), '\n'), *a.id,
                              a.bad.what);
      if (!a.id || *a.id >= kMaxId || out.meshes.count(*a.id) || !a.mesh) continue;
      out.model.append(xml.substr(copied, a.start - copied));
      out.model += placeholder(*a.id);
      copied = at = a.end;
      out.meshes.emplace(*a.id, std::move(*a.mesh));
    }
    if (!done) at = next_object(at);
  }
  if (out.meshes.empty()) {
    SplitModel none;
    none.bad = std::move(out.bad);
    return none;
  }
  out.model.append(xml.substr(copied));
  return out;
}

namespace {

// A streamed text in a window: buf_[0, size()) holds the text from some point on; what lies before
// a position handed to refill() is let go.
class Window {
 public:
  // Before an element is begun, at least this much text past it is in the window (or the text
  // ends first): an element shorter than this is read whole, a longer one is not read.
  static constexpr size_t kLook = size_t{64} << 10;
  static constexpr size_t kFill = size_t{1} << 20;  // read at once: the window is kFill + kLook

  explicit Window(const Pull& pull) : pull_(&pull), buf_(new char[kFill + kLook]), text_(buf_.get()) {}
  // The text read where `chunks` puts it.
  explicit Window(Chunks& chunks) : chunks_(&chunks) {}
  ~Window() {
    if (chunks_ && chunk_) chunks_->give_back(chunk_);
  }
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  std::string_view text() const { return {text_, size_}; }
  size_t size() const { return size_; }
  bool ended() const { return ended_; }
  // Where an element may begin: kLook before the window's end, unless the text ends in it.
  size_t limit() const { return ended_ ? std::string_view::npos : size_ - std::min(size_, kLook); }

  // Lets go of the text before `at` and reads on; `at` is moved with its text. False: the text
  // cannot be read.
  bool refill(size_t& at) {
    if (ended_) return true;
    ++refills_;
    if (chunks_) return next_chunk(at);
    std::memmove(buf_.get(), buf_.get() + at, size_ - at);
    size_ -= at;
    at = 0;
    while (size_ < kFill + kLook && !ended_) {
      const std::optional<size_t> got = (*pull_)(buf_.get() + size_, kFill + kLook - size_);
      if (!got) return false;
      ended_ = *got == 0;
      size_ += *got;
    }
    return true;
  }
  // Makes sure the window holds kLook bytes past `at` (or the rest of the text).
  bool look(size_t& at) { return size_ - at > kLook || ended_ || refill(at); }
  // How often the window has let text go.
  size_t refills() const { return refills_; }

 private:
  static_assert(Chunks::kRoom >= kLook);  // a refill keeps at most kLook bytes

  // refill() from chunks: the text from `at` on (at most kLook bytes, as every caller keeps)
  // copied into the room before the next chunk, which the window then is.
  bool next_chunk(size_t& at) {
    do {  // a short chunk is joined to the next
      const size_t tail = size_ - at;
      if (tail > Chunks::kRoom) return false;
      const std::optional<Chunks::Chunk> c = chunks_->next();
      if (!c) return false;
      if (c->size == 0) {
        ended_ = true;
        text_ += at;
        size_ = tail;
        at = 0;
        return true;
      }
      char* to = c->data + Chunks::kRoom - tail;
      if (tail) std::memcpy(to, text_ + at, tail);
      if (chunk_) chunks_->give_back(chunk_);
      chunk_ = c->data;
      text_ = to;
      size_ = tail + c->size;
      at = 0;
    } while (size_ <= kLook);
    return true;
  }

  const Pull* pull_ = nullptr;
  Chunks* chunks_ = nullptr;
  std::unique_ptr<char[]> buf_;  // the pull's window
  char* chunk_ = nullptr;        // the chunk the text is in
  const char* text_ = nullptr;
  size_t size_ = 0;
  size_t refills_ = 0;
  bool ended_ = false;
};

// Reads a run of elements (vertices() or triangles()) from `at` on, through the window's refills.
template <class T>
bool streamed_run(Window& w, size_t& at, std::vector<T>& out, Bad& bad,
                  Run (*run)(Scanner&, std::vector<T>&, size_t, Bad&)) {
  for (;;) {
    Scanner sc(w.text(), at);
    const Run r = run(sc, out, w.limit(), bad);
    at = sc.pos();
    if (r != Run::kMore) return r == Run::kDone;
    if (!w.refill(at)) return false;
  }
}

#if defined(__linux__) && defined(MADV_HUGEPAGE)
// Whether the page holding `p` is not in memory yet (memory malloc has just mapped, never used).
bool fresh_page(const void* p) {
  const uintptr_t page = reinterpret_cast<uintptr_t>(p) & ~uintptr_t{4095};
  unsigned char resident = 1;
  return mincore(reinterpret_cast<void*>(page), 4096, &resident) == 0 && !(resident & 1);
}
#endif

// Room for n elements in `v` (empty), in huge pages for the whole 2 MiB pages they will fill when
// the room is memory malloc has just mapped: a fresh process then takes one page fault for each
// 2 MiB of a mesh's arrays instead of 512 (the 3MF's meshes in bench_plate's load: 10 000 page
// faults fewer, 0.015 s of CPU). Such room is taken again, rounded up so that malloc maps memory
// of its own whose length is a whole number of 2 MiB (its header fits in the 64 bytes left), which
// the kernel places at a 2 MiB boundary (Linux 6.7 on). The rounding is address space only: the
// pages past the n elements are never touched, and those past their last whole 2 MiB stay small,
// so the memory used is what the elements need. As malloc has written its header into the first
// 2 MiB already (a small page there, which a fault would not replace), those 2 MiB are made huge
// pages at once (MADV_COLLAPSE, Linux 6.1 on). Room malloc had in use before (a process that
// loads again and again) is kept as it is: its pages are there already. Elsewhere, or when the
// system has no huge page to give, the pages are ordinary ones: only the time differs.
template <class T>
void reserve_huge(std::vector<T>& v, size_t n) {
  v.reserve(n);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr size_t kHuge = size_t{2} << 20, kHeader = 64;
  constexpr int kCollapse = 25;  // MADV_COLLAPSE (asm-generic/mman-common.h); older kernels refuse it
  const size_t bytes = n * sizeof(T);
  // (Its middle: malloc writes its headers at either end.)
  if (bytes < kHuge || !fresh_page(reinterpret_cast<const char*>(v.data()) + bytes / 2)) return;
  std::vector<T> rounded;
  try {
    rounded.reserve(((bytes + kHeader + kHuge - 1) / kHuge * kHuge - kHeader) / sizeof(T));
  } catch (const std::bad_alloc&) {  // no address space for the rounding (a limit on it): the room as it is
    return;
  }
  v.swap(rounded);  // the first room is let go untouched
  const uintptr_t at = reinterpret_cast<uintptr_t>(v.data());
  // The 2 MiB page the elements begin in, when the mapping begins there (only malloc's header
  // before them); else the next one.
  const uintptr_t from = at % kHuge <= kHeader ? at - at % kHuge : at - at % kHuge + kHuge;
  const uintptr_t to = (at + bytes) - (at + bytes) % kHuge;
  if (to > from && fresh_page(reinterpret_cast<void*>(to - kHuge / 2))) {
    madvise(reinterpret_cast<void*>(from), to - from, MADV_HUGEPAGE);  // hints: no error to see
    madvise(reinterpret_cast<void*>(from), to - from, kCollapse);
  }
#endif
}

// Memory kept from mesh to mesh (grown once) by the streamed pass.
struct Scratch {
  // Room for the vertices of most meshes (350 000 vertices, address space until written), so that
  // the first mesh's are not copied as the vector grows (bench_plate's 3MF: 300 page faults fewer).
  Scratch() { vertices.reserve(size_t{1} << 20); }
  std::vector<float> vertices;  // as read
  Bad bad;                      // a value that is no number: the whole text says where
  geo::WeldScratch weld;
};

// mesh() on a streamed text, `at` moved past it; nothing when it does not read. The vertices are
// read into `scratch` and put in the welder's order into a vector of their size; the triangles
// into room for as many as a closed mesh has (twice the vertices).
std::optional<MeshData> streamed_mesh(Window& w, size_t& at, Scratch& scratch) {
  MeshData m;
  Scanner sc(w.text(), at);
  if (!sc.start("mesh")) return std::nullopt;
  sc.skip_space();
  if (!sc.start("vertices")) return std::nullopt;
  at = sc.pos();
  scratch.vertices.clear();
  if (!streamed_run(w, at, scratch.vertices, scratch.bad, vertices) || !w.look(at)) return std::nullopt;
  const size_t nv = scratch.vertices.size() / 3;
  reserve_huge(m.triangles, 2 * nv + 1);
  reserve_huge(m.vertices, nv);  // order_by_first_use's size for them
  sc = Scanner(w.text(), at);
  sc.skip_space();
  if (!sc.start("triangles")) return std::nullopt;
  at = sc.pos();
  if (!streamed_run(w, at, m.triangles, scratch.bad, triangles) || !w.look(at)) return std::nullopt;
  sc = Scanner(w.text(), at);
  sc.skip_space();
  if (!sc.eat("</mesh>") || !complete(m.triangles, nv)) return std::nullopt;
  at = sc.pos();
  m.degenerate = geo::order_by_first_use(scratch.vertices.data(), nv, m.triangles, m.vertices, scratch.weld);
  m.ordered = true;
  return m;
}

}  // namespace

namespace {

std::optional<SplitModel> split_streamed(Window& w) {
  // split_meshes' pass, object after object, but on a window of the text. An element is read only
  // where it lies whole in the window (kLook past its start), and whatever this pass would leave
  // in place (a mesh that does not read, an object id taken twice) gives up: split_meshes, on the
  // whole text, then decides, so that a result from here is always the one it gives.
  SplitModel out;
  Scratch scratch;
  size_t at = 0;  // the text before `at` is in out.model, or was a mesh replaced
  if (!w.refill(at)) return std::nullopt;
  for (;;) {
    if (!w.look(at)) return std::nullopt;
    const std::string_view t = w.text();
    // The next "<object", by its 'j' (as find_objects()).
    size_t found = std::string_view::npos;
    for (const char* p = t.data() + std::min(at + 3, t.size()); p < t.data() + t.size();) {
      p = static_cast<const char*>(std::memchr(p, 'j', static_cast<size_t>(t.data() + t.size() - p)));
      if (!p) break;
      if (t.data() + t.size() - p >= 4 && std::memcmp(p - 3, "<object", 7) == 0) {
        found = static_cast<size_t>(p - 3 - t.data());
        break;
      }
      ++p;
    }
    if (found == std::string_view::npos) {
      if (w.ended()) {
        out.model.append(t.substr(at));
        break;
      }
      const size_t keep = std::min<size_t>(t.size() - at, 6);  // a "<object" begun at the end
      out.model.append(t.substr(at, t.size() - at - keep));
      at = t.size() - keep;
      if (!w.refill(at)) return std::nullopt;
      continue;
    }
    if (found > at) {  // the text up to it; then the tag, with kLook of text past it in the window
      out.model.append(t.substr(at, found - at));
      at = found;
      continue;
    }
    Scanner sc(t, at);
    if (!sc.open("object")) {
      out.model.append(t.substr(at, 7));
      at += 7;
      continue;
    }
    const auto tag = object_tag(sc);
    if (!tag) {  // a tag not read to its end: the rest is lib3mf's, unless the window cut it
      if (!w.ended()) return std::nullopt;
      out.model.append(t.substr(at));
      break;
    }
    out.model.append(t.substr(at, sc.pos() - at));
    at = sc.pos();
    // As split_meshes: an object with no mesh to take is passed over, the search going on after its tag.
    const std::optional<uint32_t> id = tag->id;
    if (tag->self_closed || !id || *id >= kMaxId || out.meshes.count(*id)) continue;
    if (!w.look(at)) return std::nullopt;
    sc = Scanner(w.text(), at);
    sc.skip_space();
    const size_t start = sc.pos();
    if (w.size() - start < 8 && !w.ended()) return std::nullopt;  // spaces as long as the window
    out.model.append(w.text().substr(at, start - at));
    at = start;
    if (!sc.open("mesh")) continue;  // no mesh (components): nothing more to see
    const size_t refills = w.refills();
    size_t end = start;
    std::optional<MeshData> m = streamed_mesh(w, end, scratch);
    if (!m) {
      // Passed over as well, but only where this pass saw what split_meshes sees: the whole rest
      // of the text, none of it let go. A value that is no number: the whole text says where.
      if (!scratch.bad.what.empty()) return std::nullopt;
      if (w.refills() == refills && w.ended()) continue;
      return std::nullopt;
    }
    out.model += placeholder(*id);
    out.meshes.emplace(*id, std::move(*m));
    at = end;
  }
  if (out.meshes.empty()) return SplitModel{};
  return out;
}

}  // namespace

std::optional<SplitModel> split_meshes_streamed(const Pull& pull) {
  Window w(pull);
  return split_streamed(w);
}

std::optional<SplitModel> split_meshes_streamed(Chunks& chunks) {
  Window w(chunks);
  return split_streamed(w);
}

void limit_simd(Simd most) { simd_limit.store(most); }

std::optional<uint32_t> placeholder_id(const float* a, const float* b, const float* c) {
  if (a[1] != kMarkY || a[2] != 0 || b[0] != a[0] || b[1] != kMarkY + 1 || b[2] != 0 || c[0] != a[0] ||
      c[1] != kMarkY || c[2] != 1)
    return std::nullopt;
  if (!(a[0] >= 0 && a[0] < static_cast<float>(kMaxId)) || a[0] != std::floor(a[0])) return std::nullopt;
  return static_cast<uint32_t>(a[0]);
}

}  // namespace tranche::plate::threemf
