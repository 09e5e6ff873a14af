// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A sum of doubles without round-off: every term is added exactly into a long fixed-point
// accumulator (2^-1074 to 2^1088 in base-2^32 digits held in 64-bit limbs), and only the result
// is rounded, to nearest (ties to even). The sum therefore does not depend on the order of the
// terms: threads may take any share of them, and the ranks of a distributed run may hold any part
// of a model and add their accumulators (merge, or their limbs as integers), and the result has
// the same bits as one thread summing everything. This is what makes the outputs of a run the
// same bits whatever the threads and ranks (docs/ARCHITECTURE.md, "Deterministic sums").
// Infinities and NaN propagate as in a plain sum. exact_sum() below sums a range in parallel.
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "engine/parallel_threshold.hpp"

namespace femdem {

class ExactSum {
 public:
  // 2098 bit positions from 2^-1074 (the smallest subnormal) up to the top of the double range,
  // plus headroom: 67 digits of 32 bits.
  static constexpr int kDigits = 67;
  using Limbs = std::array<std::int64_t, kDigits>;

  void add(double x) {
    const auto bits = std::bit_cast<std::uint64_t>(x);
    const int biased = static_cast<int>((bits >> 52) & 0x7ff);
    if (biased == 0x7ff) {  // inf or NaN: kept aside, as a plain sum would
      special_ += x;
      return;
    }
    std::uint64_t mantissa = bits & ((std::uint64_t{1} << 52) - 1);
    if (biased != 0) mantissa |= std::uint64_t{1} << 52;
    if (mantissa == 0) return;
    // the mantissa's lowest bit is worth 2^(biased - 1075) (2^-1074 for subnormals): bit
    // position p above 2^-1074
    const int p = biased == 0 ? 0 : biased - 1;
    const int digit = p >> 5, shift = p & 31;
    const unsigned __int128 m = static_cast<unsigned __int128>(mantissa) << shift;  // <= 85 bits
    const auto d0 = static_cast<std::int64_t>(static_cast<std::uint64_t>(m) & 0xffffffffu);
    const auto d1 = static_cast<std::int64_t>(static_cast<std::uint64_t>(m >> 32) & 0xffffffffu);
    const auto d2 = static_cast<std::int64_t>(static_cast<std::uint64_t>(m >> 64));
    if (bits >> 63) {
      limbs_[digit] -= d0;
      limbs_[digit + 1] -= d1;
      limbs_[digit + 2] -= d2;
    } else {
      limbs_[digit] += d0;
      limbs_[digit + 1] += d1;
      limbs_[digit + 2] += d2;
    }
    // each add moves a limb by less than 2^32: carry before 2^31 adds can overflow it
    if (++pending_ == kCarryEvery) normalize();
  }

  // Adds another accumulator's terms (in any order: the result is the same).
  void merge(const ExactSum& o) {
    ExactSum other = o;
    other.normalize();
    normalize();
    for (int i = 0; i < kDigits; ++i) limbs_[i] += other.limbs_[i];
    special_ += other.special_;
    pending_ = 2;  // each limb now below 2^33 in magnitude: two adds' worth
  }

  // The limbs with every carry done (each digit in [0, 2^32) but the top one, which carries the
  // sign): what ranks add as integers (MPI_SUM on int64 is exact), then `from_limbs`.
  Limbs normalized_limbs() const {
    ExactSum s = *this;
    s.normalize();
    return s.limbs_;
  }
  double special() const { return special_; }
  static ExactSum from_limbs(const Limbs& limbs, double special) {
    ExactSum s;
    s.limbs_ = limbs;
    s.special_ = special;
    s.pending_ = kCarryEvery / 2;  // limbs summed over up to 2^29 ranks: carry soon
    return s;
  }

  // The exact sum rounded to the nearest double (ties to even); +-inf past the double range.
  double value() const {
    if (special_ != 0.0 || std::isnan(special_)) return special_;
    ExactSum s = *this;
    s.normalize();
    Limbs d = s.limbs_;
    const bool negative = d[kDigits - 1] < 0;
    if (negative) negate(d);
    int top = kDigits - 1;
    while (top >= 0 && d[top] == 0) --top;
    if (top < 0) return 0.0;
    // the 96 bits from the highest non-zero digit down, and whether anything lies below them
    unsigned __int128 window = 0;
    for (int i = top; i > top - 3; --i)
      window = (window << 32) | static_cast<std::uint64_t>(i >= 0 ? d[i] : 0);
    bool sticky = false;
    for (int i = top - 3; i >= 0; --i) sticky = sticky || d[i] != 0;
    // window * 2^(32 (top - 2) - 1074) is the magnitude, up to the sticky bits
    const int lead = 127 - clz128(window);  // highest set bit of the window
    int exponent = 32 * (top - 2) - 1074;   // weight of the window's lowest bit
    // keep 53 significant bits (fewer where the result is subnormal: the lowest bit kept is
    // never below 2^-1074)
    int drop = lead + 1 - 53;
    if (exponent + drop < -1074) drop = -1074 - exponent;
    // (the window's top digit is non-zero, so it holds at least 65 significant bits: drop > 0)
    const unsigned __int128 one = 1;
    unsigned __int128 kept = window >> drop;
    const unsigned __int128 rest = window & ((one << drop) - 1), half = one << (drop - 1);
    if (rest > half || (rest == half && (sticky || (kept & 1)))) ++kept;  // nearest, ties even
    const double result =
        std::ldexp(static_cast<double>(static_cast<std::uint64_t>(kept)), exponent + drop);
    return negative ? -result : result;
  }

 private:
  static constexpr int kCarryEvery = 1 << 30;

  static int clz128(unsigned __int128 x) {
    const auto hi = static_cast<std::uint64_t>(x >> 64);
    return hi != 0 ? std::countl_zero(hi) : 64 + std::countl_zero(static_cast<std::uint64_t>(x));
  }

  // every digit but the top one into [0, 2^32), the carries (arithmetic shifts: floor) upwards
  void normalize() {
    for (int i = 0; i < kDigits - 1; ++i) {
      const std::int64_t carry = limbs_[i] >> 32;
      limbs_[i] -= carry * (std::int64_t{1} << 32);
      limbs_[i + 1] += carry;
    }
    pending_ = 0;
  }

  // two's complement over normalized digits: the magnitude of a negative sum
  static void negate(Limbs& d) {
    std::int64_t borrow = 0;
    for (int i = 0; i < kDigits; ++i) {
      std::int64_t v = -d[i] - borrow;
      borrow = 0;
      if (i < kDigits - 1 && v < 0) {
        v += std::int64_t{1} << 32;
        borrow = 1;
      }
      d[i] = v;
    }
  }

  Limbs limbs_{};
  double special_ = 0.0;
  int pending_ = 0;
};

// The exact sum over i in [0, n) of term(i), in parallel: each thread adds its share into its
// own accumulator, and the accumulators are merged (in whatever order the threads finish: the
// result is the same). `exact_sum_of` gives the accumulator, for ranks to add theirs.
template <class Term>
ExactSum exact_sum_of(std::int64_t n, Term term) {
  ExactSum total;
#pragma omp parallel if (n > kParallelMinElements)
  {
    ExactSum mine;
#pragma omp for schedule(static) nowait
    for (std::int64_t i = 0; i < n; ++i) mine.add(term(i));
#pragma omp critical(femdem_exact_sum)
    total.merge(mine);
  }
  return total;
}

template <class Term>
double exact_sum(std::int64_t n, Term term) {
  return exact_sum_of(n, term).value();
}

}  // namespace femdem
