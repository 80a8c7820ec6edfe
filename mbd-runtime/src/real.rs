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
                #[cfg(feature = "std")]
                return $t::sin(self);
                #[cfg(not(feature = "std"))]
                return libm::$sin(self);
            }
            #[inline(always)]
            fn cos(self) -> Self {
                #[cfg(feature = "std")]
                return $t::cos(self);
                #[cfg(not(feature = "std"))]
                return libm::$cos(self);
            }
            #[inline(always)]
            fn sin_cos(self) -> (Self, Self) {
                #[cfg(feature = "std")]
                return $t::sin_cos(self);
                #[cfg(not(feature = "std"))]
                return libm::$sincos(self);
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
