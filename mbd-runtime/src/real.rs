//! The scalar type of a mechanism: `f64` (the default) or `f32` (small embedded targets).
//!
//! Generated code calls every elementary function through this trait, so the same emitted
//! code runs with `std` (the platform's libm through the inherent float methods) and without
//! it (the pure-Rust `libm` crate).

use core::fmt::{Debug, Display};
use core::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

/// A real scalar usable by mechanisms and solvers. Implemented for `f32` and `f64`.
pub trait Real:
    Copy
    + Default
    + PartialOrd
    + Debug
    + Display
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
    + DivAssign
    + nalgebra::Scalar
    + nalgebra::ClosedAddAssign
    + nalgebra::ClosedSubAssign
    + nalgebra::ClosedMulAssign
    + num_traits::Zero
    + num_traits::One
    + 'static
{
    /// 0
    const ZERO: Self;
    /// 1
    const ONE: Self;
    /// Machine epsilon of the type.
    const EPSILON: Self;
    /// Name of the type as written in Rust (`"f64"`).
    const NAME: &'static str;
    /// Converts from `f64` (rounding for `f32`).
    fn from_f64(v: f64) -> Self;
    /// Converts to `f64` (exact).
    fn to_f64(self) -> f64;
    /// |x|
    fn abs(self) -> Self;
    /// sin x (x in rad)
    fn sin(self) -> Self;
    /// cos x (x in rad)
    fn cos(self) -> Self;
    /// (sin x, cos x), computed together where the platform allows.
    fn sin_cos(self) -> (Self, Self);
    /// tan x
    fn tan(self) -> Self;
    /// asin x
    fn asin(self) -> Self;
    /// acos x
    fn acos(self) -> Self;
    /// atan x
    fn atan(self) -> Self;
    /// atan2(y = self, x)
    fn atan2(self, x: Self) -> Self;
    /// √x
    fn sqrt(self) -> Self;
    /// self · a + b, as one fused multiply-add (one rounding) where the target has the
    /// instruction and `std` is on (`cfg(target_feature = "fma")`: `-C target-cpu=native` on a
    /// processor with FMA), else `self * a + b` (two roundings, the same code as written out).
    /// The generated code writes its products-plus-sums with it, as a C compiler contracts them.
    #[inline(always)]
    fn fused_mul_add(self, a: Self, b: Self) -> Self {
        self * a + b
    }
    /// eˣ
    fn exp(self) -> Self;
    /// ln x
    fn ln(self) -> Self;
    /// xⁿ for an integer n
    fn powi(self, n: i32) -> Self;
    /// xʸ for a real y
    fn powf(self, y: Self) -> Self;
    /// Whether the value is neither infinite nor NaN.
    fn is_finite(self) -> bool;
    /// The larger of two values (NaN-ignoring, like `f64::max`).
    fn max(self, other: Self) -> Self;
    /// The smaller of two values (NaN-ignoring, like `f64::min`).
    fn min(self, other: Self) -> Self;
}

/// sin, cos and both of one angle (`trig!(type, x, std's method, libm's function)`). In f64,
/// the libm crate's (musl's, FreeBSD's kernels: below 1 ulp) with or without `std`: the
/// platform's `f64::sin_cos` (glibc's `sincos` here) took 13 ns a call against 8.4 in a loop of
/// independent calls, and the generated planar kernels spend most of their time in it (issue
/// 41). All three from the one library, so that a function that needs only a cosine and a fused
/// evaluation that shares a `sin_cos` agree bitwise. Within 1 ulp of glibc's over 2.8e6 angles
/// up to 1e7 rad, multiples of π/2 among them (`trig_is_within_an_ulp_of_the_platforms` below);
/// the same sines and cosines with and without `std`. In f32, the platform's with `std`.
macro_rules! trig {
    (f64, $x:expr, $method:ident, $libm:ident) => {
        libm::$libm($x)
    };
    (f32, $x:expr, $method:ident, $libm:ident) => {{
        #[cfg(feature = "std")]
        return f32::$method($x);
        #[cfg(not(feature = "std"))]
        return libm::$libm($x);
    }};
}

macro_rules! impl_real {
    ($t:ident, $name:literal, $sin:ident, $cos:ident, $sincos:ident, $tan:ident, $asin:ident,
     $acos:ident, $atan:ident, $atan2:ident, $sqrt:ident, $exp:ident, $ln:ident, $pow:ident,
     $fabs:ident) => {
        impl Real for $t {
            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const EPSILON: Self = $t::EPSILON;
            const NAME: &'static str = $name;
            #[inline(always)]
            fn from_f64(v: f64) -> Self {
                v as $t
            }
            #[inline(always)]
            fn to_f64(self) -> f64 {
                self as f64
            }
            #[inline(always)]
            fn abs(self) -> Self {
                libm::$fabs(self)
            }
            #[inline(always)]
            fn sin(self) -> Self {
                trig!($t, self, sin, $sin)
            }
            #[inline(always)]
            fn cos(self) -> Self {
                trig!($t, self, cos, $cos)
            }
            #[inline(always)]
            fn sin_cos(self) -> (Self, Self) {
                trig!($t, self, sin_cos, $sincos)
            }
            #[inline(always)]
            fn tan(self) -> Self {
                #[cfg(feature = "std")]
                return $t::tan(self);
                #[cfg(not(feature = "std"))]
                return libm::$tan(self);
            }
            #[inline(always)]
            fn asin(self) -> Self {
                #[cfg(feature = "std")]
                return $t::asin(self);
                #[cfg(not(feature = "std"))]
                return libm::$asin(self);
            }
            #[inline(always)]
            fn acos(self) -> Self {
                #[cfg(feature = "std")]
                return $t::acos(self);
                #[cfg(not(feature = "std"))]
                return libm::$acos(self);
            }
            #[inline(always)]
            fn atan(self) -> Self {
                #[cfg(feature = "std")]
                return $t::atan(self);
                #[cfg(not(feature = "std"))]
                return libm::$atan(self);
            }
            #[inline(always)]
            fn atan2(self, x: Self) -> Self {
                #[cfg(feature = "std")]
                return $t::atan2(self, x);
                #[cfg(not(feature = "std"))]
                return libm::$atan2(self, x);
            }
            #[inline(always)]
            fn fused_mul_add(self, a: Self, b: Self) -> Self {
                #[cfg(all(feature = "std", target_feature = "fma"))]
                return $t::mul_add(self, a, b);
                #[cfg(not(all(feature = "std", target_feature = "fma")))]
                return self * a + b;
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                #[cfg(feature = "std")]
                return $t::sqrt(self);
                #[cfg(not(feature = "std"))]
                return libm::$sqrt(self);
            }
            #[inline(always)]
            fn exp(self) -> Self {
                #[cfg(feature = "std")]
                return $t::exp(self);
                #[cfg(not(feature = "std"))]
                return libm::$exp(self);
            }
            #[inline(always)]
            fn ln(self) -> Self {
                #[cfg(feature = "std")]
                return $t::ln(self);
                #[cfg(not(feature = "std"))]
                return libm::$ln(self);
            }
            #[inline(always)]
            fn powi(self, n: i32) -> Self {
                #[cfg(feature = "std")]
                return $t::powi(self, n);
                #[cfg(not(feature = "std"))]
                return libm::$pow(self, n as $t);
            }
            #[inline(always)]
            fn powf(self, y: Self) -> Self {
                #[cfg(feature = "std")]
                return $t::powf(self, y);
                #[cfg(not(feature = "std"))]
                return libm::$pow(self, y);
            }
            #[inline(always)]
            fn is_finite(self) -> bool {
                $t::is_finite(self)
            }
            #[inline(always)]
            fn max(self, other: Self) -> Self {
                if self >= other || other != other {
                    self
                } else {
                    other
                }
            }
            #[inline(always)]
            fn min(self, other: Self) -> Self {
                if self <= other || other != other {
                    self
                } else {
                    other
                }
            }
        }
    };
}

impl_real!(f64, "f64", sin, cos, sincos, tan, asin, acos, atan, atan2, sqrt, exp, log, pow, fabs);
impl_real!(f32, "f32", sinf, cosf, sincosf, tanf, asinf, acosf, atanf, atan2f, sqrtf, expf, logf, powf, fabsf);

#[cfg(all(test, feature = "std"))]
mod tests {
    use super::Real;

    /// The largest distance in ulps between two finite doubles of the same sign.
    fn ulps(a: f64, b: f64) -> u64 {
        (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs()
    }

    /// `Real::sin_cos`, `sin` and `cos` in f64 (the libm crate's) against the platform's
    /// (glibc's, itself within an ulp): at most 1 ulp apart — so within 2 ulps of the exact
    /// values, issue 41's bound for a faster `sin_cos` — and `sin_cos` equal to `sin` and `cos`
    /// bitwise, on angles log-spaced from 1e-300 to 1e7 rad (the range a run's angles take: a
    /// flywheel after 10 s at 5 rev/s is at 314 rad) of both signs, and on the three doubles
    /// either side of each of the first 200 000 multiples of π/2, where the argument's
    /// reduction cancels most.
    #[test]
    fn trig_is_within_an_ulp_of_the_platforms() {
        let (mut worst, mut count) = (0, 0);
        let mut probe = |x: f64| {
            let (s, c) = Real::sin_cos(x);
            let (s0, c0) = x.sin_cos();
            let d = ulps(s, s0).max(ulps(c, c0));
            worst = worst.max(d);
            count += 1;
            assert!(d <= 1, "sin_cos({x:e}) = ({s:e}, {c:e}), the platform's ({s0:e}, {c0:e})");
            assert!(Real::sin(x) == s && Real::cos(x) == c, "sin_cos({x:e}) is not (sin, cos)");
        };
        let mut x = 1e-300f64;
        while x < 1e7 {
            probe(x);
            probe(-x);
            x *= 1.001;
        }
        for k in 1..200_000i64 {
            let b = (k as f64 * core::f64::consts::FRAC_PI_2).to_bits() as i64;
            for d in -3..=3 {
                probe(f64::from_bits((b + d) as u64));
            }
        }
        assert!(count > 1_000_000 && worst <= 1, "{count} angles, {worst} ulps");
    }
}
