// SPDX-License-Identifier: GPL-3.0-or-later
// ExactSum (engine/exact_sum.hpp): the correctly rounded sum whatever the order of the terms.
// References that do not use the accumulator: hand-worked cases (Python's math.fsum gives the
// same), and sums of integers times a power of two done exactly in 128-bit integers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "engine/exact_sum.hpp"

using femdem::ExactSum;

namespace {

double exact(const std::vector<double>& terms) {
  ExactSum s;
  for (double t : terms) s.add(t);
  return s.value();
}

}  // namespace

TEST(ExactSum, CancellationThatAPlainSumGetsWrong) {
  EXPECT_EQ(exact({1e16, 1.0, -1e16}), 1.0);  // a plain sum: 0
  EXPECT_EQ(exact({1.0, 1e100, 1.0, -1e100}), 2.0);
  EXPECT_EQ(exact({1e308, 1e308, -1e308}), 1e308);      // no overflow on the way
  EXPECT_EQ(exact(std::vector<double>(10, 0.1)), 1.0);  // the correctly rounded answer
  EXPECT_EQ(exact({0.1, 0.2}), 0.1 + 0.2);              // two terms: one rounding, as IEEE addition
  EXPECT_EQ(exact({}), 0.0);
  EXPECT_EQ(exact({-3.5, 1.25}), -2.25);
  // ties to even: 2^53 + 1 is halfway between 2^53 and 2^53 + 2
  const double two53 = 9007199254740992.0;
  EXPECT_EQ(exact({two53, 1.0}), two53);
  EXPECT_EQ(exact({two53, 1.0, 1e-300}), two53 + 2.0);  // just above halfway: up
  EXPECT_EQ(exact({two53 + 2.0, 1.0}), two53 + 4.0);    // halfway, odd below: up
}

TEST(ExactSum, SubnormalsInfinitiesAndNan) {
  const double tiny = std::numeric_limits<double>::denorm_min();
  EXPECT_EQ(exact({tiny, tiny, tiny}), 3 * tiny);
  EXPECT_EQ(exact({std::numeric_limits<double>::min(), -tiny}),
            std::numeric_limits<double>::min() - tiny);
  EXPECT_EQ(exact({1.0, -1.0, tiny}), tiny);
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(exact({1.0, inf}), inf);
  EXPECT_EQ(exact({1.0, -inf}), -inf);
  EXPECT_TRUE(std::isnan(exact({inf, -inf})));
  EXPECT_TRUE(std::isnan(exact({1.0, std::nan("")})));
  EXPECT_EQ(exact({1e308, 1e308}), inf);  // past the range, as IEEE addition
  EXPECT_EQ(exact({-1e308, -1e308}), -inf);
}

TEST(ExactSum, MatchesIntegerArithmeticInAnyOrderAndSplit) {
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<std::int64_t> mant(-(std::int64_t{1} << 52), std::int64_t{1} << 52);
  std::uniform_int_distribution<int> shift(0, 60), count(1, 400);
  for (int trial = 0; trial < 300; ++trial) {
    // terms m * 2^(s - 80) with |m| < 2^53: exact in 128-bit integers in units of 2^-80
    const int n = count(rng);
    std::vector<double> terms;
    __int128 total = 0;
    for (int k = 0; k < n; ++k) {
      const std::int64_t m = mant(rng);
      const int s = shift(rng);
      terms.push_back(std::ldexp(static_cast<double>(m), s - 80));
      total += static_cast<__int128>(m) << s;
    }
    // (__int128 to double is correctly rounded; the power-of-two scaling is exact)
    const double reference = std::ldexp(static_cast<double>(total), -80);
    EXPECT_EQ(exact(terms), reference) << "trial " << trial;
    std::shuffle(terms.begin(), terms.end(), rng);
    EXPECT_EQ(exact(terms), reference) << "trial " << trial << ", shuffled";
    // split in three, summed apart, then merged (threads) or added as limbs (ranks)
    ExactSum a, b, c;
    for (int k = 0; k < n; ++k) (k % 3 == 0 ? a : k % 3 == 1 ? b : c).add(terms[k]);
    ExactSum merged = c;
    merged.merge(a);
    merged.merge(b);
    EXPECT_EQ(merged.value(), reference) << "trial " << trial << ", merged";
    ExactSum::Limbs limbs{};
    for (const ExactSum* part : {&a, &b, &c}) {
      const ExactSum::Limbs l = part->normalized_limbs();
      for (int i = 0; i < ExactSum::kDigits; ++i) limbs[i] += l[i];
    }
    EXPECT_EQ(ExactSum::from_limbs(limbs, 0.0).value(), reference) << "trial " << trial;
  }
}

TEST(ExactSum, ManyTermsOfMixedSigns) {
  // 3 million terms of all magnitudes and their negatives in another order: exactly zero, and
  // with one extra term, exactly that term
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> e(-300, 300);
  std::vector<double> terms;
  for (int k = 0; k < 1500000; ++k) terms.push_back(std::ldexp(u(rng), e(rng)));
  std::vector<double> negatives(terms.rbegin(), terms.rend());
  ExactSum s;
  for (double t : terms) s.add(t);
  for (double t : negatives) s.add(-t);
  EXPECT_EQ(s.value(), 0.0);
  s.add(0.3);
  EXPECT_EQ(s.value(), 0.3);
}
