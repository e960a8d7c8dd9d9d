#include "geometry/gcode/numbers.h"

namespace tranche::gcode {

void append_int(std::string& out, int64_t v) {
  char buf[24];
  int n = 0;
  bool neg = v < 0;
  uint64_t u = neg ? static_cast<uint64_t>(-(v + 1)) + 1 : static_cast<uint64_t>(v);
  do {
    buf[n++] = static_cast<char>('0' + u % 10);
    u /= 10;
  } while (u);
  if (neg) out.push_back('-');
  while (n) out.push_back(buf[--n]);
}

void append_fixed(std::string& out, int64_t scaled, int decimals) {
  static constexpr int64_t kPow[] = {1, 10, 100, 1000, 10000, 100000, 1000000, 10000000, 100000000};
  int64_t p = kPow[decimals];
  bool neg = scaled < 0;
  uint64_t u = neg ? static_cast<uint64_t>(-(scaled + 1)) + 1 : static_cast<uint64_t>(scaled);
  uint64_t ip = u / static_cast<uint64_t>(p), fp = u % static_cast<uint64_t>(p);
  if (neg) out.push_back('-');
  append_int(out, static_cast<int64_t>(ip));
  if (fp == 0) return;
  char digits[8];
  int n = decimals;
  for (int i = decimals - 1; i >= 0; --i) {
    digits[i] = static_cast<char>('0' + fp % 10);
    fp /= 10;
  }
  while (n > 0 && digits[n - 1] == '0') --n;
  out.push_back('.');
  out.append(digits, static_cast<size_t>(n));
}

}  // namespace tranche::gcode
