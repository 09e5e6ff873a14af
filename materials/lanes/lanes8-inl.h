// SPDX-License-Identifier: GPL-3.0-or-later
// Per-instruction-set header (Highway's "-inl.h" pattern: included once per target from inside
// HWY_NAMESPACE by the per-target element code (engine/element_update/), never on its own).
//
// Lanes8: eight doubles, the 4 Gauss points of two elements (lanes 0-3 the first element,
// 4-7 the second), whatever the vector width: one AVX-512 vector, two AVX2 vectors, or eight
// one-lane ones (Highway's portable SCALAR target). Element code is written once on Lanes8
// and compiled for each instruction set; two elements per pack also give the out-of-order core
// two independent chains (worth about 1.4x in cache on this kernel). Arithmetic, comparisons, select,
// sqrt, log and exp act lane by lane; the only cross-lane operations are the per-element sums
// and extremes (sum4, min4, max4) and the loads that broadcast a per-element value.
#if defined(FEMDEM_LANES8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef FEMDEM_LANES8_INL_H_
#undef FEMDEM_LANES8_INL_H_
#else
#define FEMDEM_LANES8_INL_H_
#endif

#include <hwy/contrib/math/math-inl.h>
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace femdem::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The 8-lane (AVX-512) halves operations exist on every target but the 1-lane HWY_SCALAR.
#define FEMDEM_LANES8_HALVES (HWY_TARGET != HWY_SCALAR)

using LaneTag = hn::ScalableTag<double>;
using LaneVec = hn::Vec<LaneTag>;
using LaneMask = hn::Mask<LaneTag>;
inline constexpr std::size_t kLanesPerVec = hn::MaxLanes(LaneTag());
static_assert(kLanesPerVec <= 8 && 8 % kLanesPerVec == 0);
inline constexpr int kParts = static_cast<int>(8 / kLanesPerVec);

struct Lanes8 {
  LaneVec v[kParts];
  HWY_INLINE Lanes8() = default;
  HWY_INLINE Lanes8(double x) {  // NOLINT: a constant in every lane
    for (int i = 0; i < kParts; ++i) v[i] = hn::Set(LaneTag(), x);
  }
};

struct Mask8 {
  LaneMask m[kParts];
};

#define FEMDEM_LANES8_BINARY(op, expr)                     \
  HWY_INLINE Lanes8 op(const Lanes8& a, const Lanes8& b) { \
    Lanes8 r;                                              \
    for (int i = 0; i < kParts; ++i) r.v[i] = expr;        \
    return r;                                              \
  }
FEMDEM_LANES8_BINARY(operator+, a.v[i] + b.v[i])
FEMDEM_LANES8_BINARY(operator-, a.v[i] - b.v[i])
FEMDEM_LANES8_BINARY(operator*, a.v[i] * b.v[i])
FEMDEM_LANES8_BINARY(operator/, a.v[i] / b.v[i])
FEMDEM_LANES8_BINARY(min, hn::Min(a.v[i], b.v[i]))
FEMDEM_LANES8_BINARY(max, hn::Max(a.v[i], b.v[i]))
#undef FEMDEM_LANES8_BINARY

HWY_INLINE Mask8 operator<(const Lanes8& a, const Lanes8& b) {
  Mask8 r;
  for (int i = 0; i < kParts; ++i) r.m[i] = a.v[i] < b.v[i];
  return r;
}
HWY_INLINE Mask8 operator<=(const Lanes8& a, const Lanes8& b) {
  Mask8 r;
  for (int i = 0; i < kParts; ++i) r.m[i] = a.v[i] <= b.v[i];
  return r;
}
HWY_INLINE Mask8 operator>(const Lanes8& a, const Lanes8& b) {
  return b < a;
}
HWY_INLINE Mask8 operator>=(const Lanes8& a, const Lanes8& b) {
  return b <= a;
}
HWY_INLINE Mask8 operator==(const Lanes8& a, const Lanes8& b) {
  Mask8 r;
  for (int i = 0; i < kParts; ++i) r.m[i] = a.v[i] == b.v[i];
  return r;
}

HWY_INLINE Mask8 operator!=(const Lanes8& a, const Lanes8& b) {
  Mask8 r;
  for (int i = 0; i < kParts; ++i) r.m[i] = a.v[i] != b.v[i];
  return r;
}

HWY_INLINE Lanes8 operator-(const Lanes8& a) {
  Lanes8 r;
  for (int i = 0; i < kParts; ++i) r.v[i] = hn::Neg(a.v[i]);
  return r;
}
HWY_INLINE Lanes8& operator+=(Lanes8& a, const Lanes8& b) {
  return a = a + b;
}
HWY_INLINE Lanes8& operator-=(Lanes8& a, const Lanes8& b) {
  return a = a - b;
}
HWY_INLINE Lanes8& operator*=(Lanes8& a, const Lanes8& b) {
  return a = a * b;
}

HWY_INLINE Mask8 operator&(const Mask8& a, const Mask8& b) {
  Mask8 r;
  for (int i = 0; i < kParts; ++i) r.m[i] = hn::And(a.m[i], b.m[i]);
  return r;
}
HWY_INLINE Mask8 operator|(const Mask8& a, const Mask8& b) {
  Mask8 r;
  for (int i = 0; i < kParts; ++i) r.m[i] = hn::Or(a.m[i], b.m[i]);
  return r;
}
HWY_INLINE Mask8 operator!(const Mask8& a) {
  Mask8 r;
  for (int i = 0; i < kParts; ++i) r.m[i] = hn::Not(a.m[i]);
  return r;
}
HWY_INLINE Mask8& operator&=(Mask8& a, const Mask8& b) {
  return a = a & b;
}
HWY_INLINE Mask8& operator|=(Mask8& a, const Mask8& b) {
  return a = a | b;
}

// m ? a : b, lane by lane.
HWY_INLINE Lanes8 select(const Mask8& m, const Lanes8& a, const Lanes8& b) {
  Lanes8 r;
  for (int i = 0; i < kParts; ++i) r.v[i] = hn::IfThenElse(m.m[i], a.v[i], b.v[i]);
  return r;
}
HWY_INLINE bool any(const Mask8& m) {
  for (int i = 0; i < kParts; ++i)
    if (!hn::AllFalse(LaneTag(), m.m[i])) return true;
  return false;
}
HWY_INLINE Mask8 all_lanes(bool on) {
  const Lanes8 z(0.0);
  return on ? (z == z) : (z < z);
}

// a * b + c (fused where the instruction set has it).
HWY_INLINE Lanes8 mul_add(const Lanes8& a, const Lanes8& b, const Lanes8& c) {
  Lanes8 r;
  for (int i = 0; i < kParts; ++i) r.v[i] = hn::MulAdd(a.v[i], b.v[i], c.v[i]);
  return r;
}
HWY_INLINE Lanes8 sqrt(const Lanes8& a) {
  Lanes8 r;
  for (int i = 0; i < kParts; ++i) r.v[i] = hn::Sqrt(a.v[i]);
  return r;
}
HWY_INLINE Lanes8 abs(const Lanes8& a) {
  Lanes8 r;
  for (int i = 0; i < kParts; ++i) r.v[i] = hn::Abs(a.v[i]);
  return r;
}
HWY_INLINE Lanes8 log(const Lanes8& a) {
  Lanes8 r;
  for (int i = 0; i < kParts; ++i) r.v[i] = hn::Log(LaneTag(), a.v[i]);
  return r;
}
HWY_INLINE Lanes8 exp(const Lanes8& a) {
  Lanes8 r;
  for (int i = 0; i < kParts; ++i) r.v[i] = hn::Exp(LaneTag(), a.v[i]);
  return r;
}
// a^(1/3) for a > 0: exp(ln(a) / 3), then a Newton step on y^3 = a, which takes the few ulp
// that the division by 3 and the vector log and exp leave to about one (as std::cbrt).
HWY_INLINE Lanes8 cbrt_positive(const Lanes8& a) {
  const Lanes8 y = exp(log(a) * Lanes8(1.0 / 3.0));
  const Lanes8 y2 = y * y;
  return y - (y2 * y - a) / (Lanes8(3.0) * y2);
}

// Eight consecutive doubles.
HWY_INLINE Lanes8 load8(const double* p) {
  Lanes8 r;
  for (int i = 0; i < kParts; ++i) r.v[i] = hn::LoadU(LaneTag(), p + i * kLanesPerVec);
  return r;
}
HWY_INLINE void store8(const Lanes8& a, double* p) {
  for (int i = 0; i < kParts; ++i) hn::StoreU(a.v[i], LaneTag(), p + i * kLanesPerVec);
}

// Lanes 0-3 from p0[0..3], lanes 4-7 from p1[0..3] (each element's 4 Gauss points).
HWY_INLINE Lanes8 load_pair(const double* p0, const double* p1) {
  Lanes8 r;
#if FEMDEM_LANES8_HALVES
  if constexpr (kLanesPerVec == 8) {
    const hn::Half<LaneTag> dh;
    r.v[0] = hn::Combine(LaneTag(), hn::LoadU(dh, p1), hn::LoadU(dh, p0));
  } else
#endif
  {
    constexpr int per_element = kParts / 2;
    for (int i = 0; i < per_element; ++i) {
      r.v[i] = hn::LoadU(LaneTag(), p0 + i * kLanesPerVec);
      r.v[per_element + i] = hn::LoadU(LaneTag(), p1 + i * kLanesPerVec);
    }
  }
  return r;
}
// The inverse of load_pair (lanes 0-3 to p0, 4-7 to p1).
HWY_INLINE void store_pair(const Lanes8& a, double* p0, double* p1) {
#if FEMDEM_LANES8_HALVES
  if constexpr (kLanesPerVec == 8) {
    const hn::Half<LaneTag> dh;
    hn::StoreU(hn::LowerHalf(dh, a.v[0]), dh, p0);
    hn::StoreU(hn::UpperHalf(dh, a.v[0]), dh, p1);
  } else
#endif
  {
    constexpr int per_element = kParts / 2;
    for (int i = 0; i < per_element; ++i) {
      hn::StoreU(a.v[i], LaneTag(), p0 + i * kLanesPerVec);
      hn::StoreU(a.v[per_element + i], LaneTag(), p1 + i * kLanesPerVec);
    }
  }
}
// a in lanes 0-3, b in lanes 4-7.
HWY_INLINE Lanes8 pair(double a, double b) {
  Lanes8 r;
#if FEMDEM_LANES8_HALVES
  if constexpr (kLanesPerVec == 8) {
    const hn::Half<LaneTag> dh;
    r.v[0] = hn::Combine(LaneTag(), hn::Set(dh, b), hn::Set(dh, a));
  } else
#endif
  {
    constexpr int per_element = kParts / 2;
    for (int i = 0; i < per_element; ++i) {
      r.v[i] = hn::Set(LaneTag(), a);
      r.v[per_element + i] = hn::Set(LaneTag(), b);
    }
  }
  return r;
}

// Per element: the sum (or least, or largest) of its 4 lanes, as two doubles. The order of the
// additions is fixed for an instruction set, so the result does not depend on threads.
struct PairOf {
  double first, second;
};
namespace lanes8_detail {
template <class Reduce>
HWY_INLINE PairOf reduce4(const Lanes8& a, Reduce reduce) {
#if FEMDEM_LANES8_HALVES
  if constexpr (kLanesPerVec == 8) {
    const hn::Half<LaneTag> dh;
    return {hn::GetLane(reduce(dh, hn::LowerHalf(dh, a.v[0]))),
            hn::GetLane(reduce(dh, hn::UpperHalf(dh, a.v[0])))};
  } else
#endif
  {
    alignas(64) double lanes[8];
    store8(a, lanes);
    return {reduce(lanes[0], lanes[1], lanes[2], lanes[3]),
            reduce(lanes[4], lanes[5], lanes[6], lanes[7])};
  }
}
}  // namespace lanes8_detail

HWY_INLINE PairOf sum4(const Lanes8& a) {
  if constexpr (kLanesPerVec == 8) {
    return lanes8_detail::reduce4(a, [](auto d, auto v) { return hn::SumOfLanes(d, v); });
  } else {
    return lanes8_detail::reduce4(
        a, [](double x0, double x1, double x2, double x3) { return (x0 + x1) + (x2 + x3); });
  }
}
HWY_INLINE PairOf min4(const Lanes8& a) {
  if constexpr (kLanesPerVec == 8) {
    return lanes8_detail::reduce4(a, [](auto d, auto v) { return hn::MinOfLanes(d, v); });
  } else {
    return lanes8_detail::reduce4(a, [](double x0, double x1, double x2, double x3) {
      return std::fmin(std::fmin(x0, x1), std::fmin(x2, x3));
    });
  }
}
HWY_INLINE PairOf max4(const Lanes8& a) {
  if constexpr (kLanesPerVec == 8) {
    return lanes8_detail::reduce4(a, [](auto d, auto v) { return hn::MaxOfLanes(d, v); });
  } else {
    return lanes8_detail::reduce4(a, [](double x0, double x1, double x2, double x3) {
      return std::fmax(std::fmax(x0, x1), std::fmax(x2, x3));
    });
  }
}
// Each element's sum, back in all of its lanes.
HWY_INLINE Lanes8 sum4_broadcast(const Lanes8& a) {
  const PairOf s = sum4(a);
  return pair(s.first, s.second);
}

}  // namespace femdem::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // FEMDEM_LANES8_INL_H_
