// Quadruple precision (GCC's __float128, IEEE binary128: 113-bit significand, eps 1.9e-34,
// soft-float arithmetic from libgcc, math functions from libquadmath) as an Eigen scalar,
// for the mode systems that x87 long double cannot solve (docs/spectral.md, "Precision").
//
// A thin class around __float128 rather than the raw type: the project compiles with
// -std=c++20 (no GNU extensions), where libstdc++ offers no std::numeric_limits, std::abs or
// std::sqrt for __float128, and an unqualified `sqrt(x)` after Eigen's `using std::sqrt`
// would be ambiguous between the float/double/long double overloads. A class gets its math
// functions by argument-dependent lookup and its own numeric_limits and Eigen::NumTraits.
// Every member is inline: the arithmetic costs what __float128's does.
#pragma once

#include <cstdint>
#include <limits>
#include <type_traits>

#include <Eigen/Core>

namespace pdesurf::spectral {

__extension__ typedef __float128 Float128;

// libquadmath (declared here rather than through <quadmath.h>, whose FLT128_* macros use
// the Q literal suffix that strict C++ rejects).
extern "C" {
Float128 sqrtq(Float128);
Float128 fabsq(Float128);
Float128 expq(Float128);
Float128 logq(Float128);
Float128 cosq(Float128);
Float128 sinq(Float128);
Float128 powq(Float128, Float128);
Float128 ldexpq(Float128, int);
int isinfq(Float128);
int isnanq(Float128);
}

class Quad {
 public:
  Quad() = default;
  template <class A>
  requires std::is_arithmetic_v<A>
  constexpr Quad(A a) : v_(static_cast<Float128>(a)) {}  // NOLINT: implicit, like a float
  static constexpr Quad fromRaw(Float128 v) {
    Quad q;
    q.v_ = v;
    return q;
  }
  template <class A>
  requires std::is_arithmetic_v<A>
  constexpr explicit operator A() const { return static_cast<A>(v_); }
  constexpr Float128 raw() const { return v_; }

  constexpr Quad operator-() const { return fromRaw(-v_); }
  constexpr Quad operator+() const { return *this; }
  constexpr Quad& operator+=(Quad o) {
    v_ += o.v_;
    return *this;
  }
  constexpr Quad& operator-=(Quad o) {
    v_ -= o.v_;
    return *this;
  }
  constexpr Quad& operator*=(Quad o) {
    v_ *= o.v_;
    return *this;
  }
  constexpr Quad& operator/=(Quad o) {
    v_ /= o.v_;
    return *this;
  }
  friend constexpr Quad operator+(Quad a, Quad b) { return fromRaw(a.v_ + b.v_); }
  friend constexpr Quad operator-(Quad a, Quad b) { return fromRaw(a.v_ - b.v_); }
  friend constexpr Quad operator*(Quad a, Quad b) { return fromRaw(a.v_ * b.v_); }
  friend constexpr Quad operator/(Quad a, Quad b) { return fromRaw(a.v_ / b.v_); }
  friend constexpr bool operator==(Quad a, Quad b) { return a.v_ == b.v_; }
  friend constexpr bool operator!=(Quad a, Quad b) { return a.v_ != b.v_; }
  friend constexpr bool operator<(Quad a, Quad b) { return a.v_ < b.v_; }
  friend constexpr bool operator<=(Quad a, Quad b) { return a.v_ <= b.v_; }
  friend constexpr bool operator>(Quad a, Quad b) { return a.v_ > b.v_; }
  friend constexpr bool operator>=(Quad a, Quad b) { return a.v_ >= b.v_; }

 private:
  Float128 v_;
};

// Found by argument-dependent lookup (Eigen calls `using std::sqrt; sqrt(x);`).
inline Quad sqrt(Quad x) { return Quad::fromRaw(sqrtq(x.raw())); }
inline Quad abs(Quad x) { return Quad::fromRaw(fabsq(x.raw())); }
inline Quad fabs(Quad x) { return abs(x); }
inline Quad exp(Quad x) { return Quad::fromRaw(expq(x.raw())); }
inline Quad log(Quad x) { return Quad::fromRaw(logq(x.raw())); }
inline Quad cos(Quad x) { return Quad::fromRaw(cosq(x.raw())); }
inline Quad sin(Quad x) { return Quad::fromRaw(sinq(x.raw())); }
inline Quad pow(Quad x, Quad y) { return Quad::fromRaw(powq(x.raw(), y.raw())); }
inline bool isnan(Quad x) { return isnanq(x.raw()) != 0; }
inline bool isinf(Quad x) { return isinfq(x.raw()) != 0; }
inline bool isfinite(Quad x) { return !isnan(x) && !isinf(x); }

/// x = hi + lo exactly, hi = x rounded to long double (lo has at most 50 significant bits,
/// so it is exact in long double too): how quad coefficients are stored in the patch.
inline void split(Quad x, long double& hi, long double& lo) {
  hi = static_cast<long double>(x);
  lo = static_cast<long double>(x - Quad(hi));
}
inline Quad join(long double hi, long double lo) { return Quad(hi) + Quad(lo); }

using MatrixQ = Eigen::Matrix<Quad, Eigen::Dynamic, Eigen::Dynamic>;
using RowVectorQ = Eigen::Matrix<Quad, 1, Eigen::Dynamic>;

}  // namespace pdesurf::spectral

template <>
class std::numeric_limits<pdesurf::spectral::Quad> {
  using Q = pdesurf::spectral::Quad;

 public:
  static constexpr bool is_specialized = true;
  static constexpr bool is_signed = true;
  static constexpr bool is_integer = false;
  static constexpr bool is_exact = false;
  static constexpr bool has_infinity = true;
  static constexpr bool has_quiet_NaN = true;
  static constexpr bool has_signaling_NaN = false;
  static constexpr bool is_iec559 = true;
  static constexpr bool is_bounded = true;
  static constexpr bool is_modulo = false;
  static constexpr int radix = 2;
  static constexpr int digits = 113;
  static constexpr int digits10 = 33;
  static constexpr int max_digits10 = 36;
  static constexpr int min_exponent = -16381;
  static constexpr int max_exponent = 16384;
  static constexpr int min_exponent10 = -4931;
  static constexpr int max_exponent10 = 4932;
  static constexpr std::float_round_style round_style = std::round_to_nearest;
  static Q epsilon() { return Q(0x1p-112); }  // exact in double
  static Q round_error() { return Q(0.5); }
  static Q min() { return Q::fromRaw(pdesurf::spectral::ldexpq(1, -16382)); }
  static Q max() {
    return Q::fromRaw(pdesurf::spectral::ldexpq(2 - pdesurf::spectral::ldexpq(1, -112), 16383));
  }
  static Q lowest() { return -max(); }
  static Q denorm_min() { return Q::fromRaw(pdesurf::spectral::ldexpq(1, -16494)); }
  static Q infinity() { return Q(std::numeric_limits<double>::infinity()); }
  static Q quiet_NaN() { return Q(std::numeric_limits<double>::quiet_NaN()); }
};

template <>
struct Eigen::NumTraits<pdesurf::spectral::Quad>
    : Eigen::GenericNumTraits<pdesurf::spectral::Quad> {
  using Real = pdesurf::spectral::Quad;
  using NonInteger = pdesurf::spectral::Quad;
  using Nested = pdesurf::spectral::Quad;
  using Literal = pdesurf::spectral::Quad;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 0,
    ReadCost = 1,
    AddCost = 20,  // soft-float: ~20 double additions' time
    MulCost = 20
  };
  static Real epsilon() { return std::numeric_limits<Real>::epsilon(); }
  static Real dummy_precision() { return Real(1e-30); }
  static Real highest() { return (std::numeric_limits<Real>::max)(); }
  static Real lowest() { return std::numeric_limits<Real>::lowest(); }
  static Real infinity() { return std::numeric_limits<Real>::infinity(); }
  static Real quiet_NaN() { return std::numeric_limits<Real>::quiet_NaN(); }
  static int digits10() { return 33; }
  static int digits() { return 113; }
};
