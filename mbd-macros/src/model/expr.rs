//! Resolved expressions (`MExpr`) and where they may appear (`Scope`).

use super::*;

/// A resolved expression.
#[derive(Clone, Debug)]
pub enum MExpr {
    Num(f64),
    Pi,
    T,
    Param(usize),
    Coord(BodyRef, Coord),
    /// A body velocity (force expressions only).
    Vel(BodyRef, Vel),
    Neg(Box<MExpr>),
    Bin(MBin, Box<MExpr>, Box<MExpr>),
    Call(Func, Box<MExpr>),
    Atan2(Box<MExpr>, Box<MExpr>),
    /// `abs`, `sign`, `min`, `max` or `clamp` of its arguments.
    Kink(Kink, Box<[MExpr]>),
    /// `if a cmp b { x } else { y }`, `<` and `<=` written as `>` and `>=` with the operands
    /// swapped: `[a, b, x, y]`.
    If(Cmp, Box<[MExpr; 4]>),
}

/// The non-smooth functions (`sym::Graph::abs` … define them and their derivatives at the kink).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kink {
    Abs,
    Sign,
    Min,
    Max,
    Clamp,
}

impl Kink {
    pub const ALL: [Kink; 5] = [Kink::Abs, Kink::Sign, Kink::Min, Kink::Max, Kink::Clamp];

    pub fn name(self) -> &'static str {
        match self {
            Kink::Abs => "abs",
            Kink::Sign => "sign",
            Kink::Min => "min",
            Kink::Max => "max",
            Kink::Clamp => "clamp",
        }
    }

    pub fn arity(self) -> usize {
        match self {
            Kink::Abs | Kink::Sign => 1,
            Kink::Min | Kink::Max => 2,
            Kink::Clamp => 3,
        }
    }

    pub fn from_name(name: &str) -> Option<Kink> {
        Kink::ALL.into_iter().find(|k| k.name() == name)
    }

    /// Its value, defined as the graph defines it (`sign(0) = 0`; `clamp` tests `lo` first).
    pub fn apply(self, a: &[f64]) -> f64 {
        match self {
            Kink::Abs => a[0].abs(),
            Kink::Sign if a[0] > 0.0 => 1.0,
            Kink::Sign if a[0] < 0.0 => -1.0,
            Kink::Sign => 0.0,
            Kink::Min => {
                if a[1] >= a[0] {
                    a[0]
                } else {
                    a[1]
                }
            }
            Kink::Max => {
                if a[0] >= a[1] {
                    a[0]
                } else {
                    a[1]
                }
            }
            Kink::Clamp => {
                if a[1] > a[0] {
                    a[1]
                } else if a[0] > a[2] {
                    a[2]
                } else {
                    a[0]
                }
            }
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MBin {
    Add,
    Sub,
    Mul,
    Div,
    Pow,
}

impl MExpr {
    /// The value of an expression made of numbers, `PI` and functions only.
    pub fn constant_value(&self) -> Option<f64> {
        self.value_with(&|_| None)
    }

    /// The value of an expression of numbers, `PI`, functions and parameters at the parameters'
    /// default values.
    pub fn default_value(&self, defaults: &[f64]) -> Option<f64> {
        self.value_with(&|k| defaults.get(k).copied())
    }

    /// Whether f(t) is 0 at every time, whatever the parameters (tried at a few times).
    pub fn is_zero_in_time(&self) -> bool {
        [0.0, 0.37, 1.0, 2.9].iter().all(|&t| self.value_with(&|k| (k == usize::MAX).then_some(t)) == Some(0.0))
    }

    /// The value of a driver f(t) at time t with the parameters' default values.
    pub fn value_at(&self, defaults: &[f64], t: f64) -> Option<f64> {
        self.value_with(&|k| if k == usize::MAX { Some(t) } else { defaults.get(k).copied() })
    }

    /// The value for the parameters `param(k)`; `param(usize::MAX)` is t.
    fn value_with(&self, param: &dyn Fn(usize) -> Option<f64>) -> Option<f64> {
        Some(match self {
            MExpr::Num(v) => *v,
            MExpr::Pi => std::f64::consts::PI,
            MExpr::Param(k) => return param(*k),
            MExpr::T => return param(usize::MAX),
            MExpr::Coord(..) | MExpr::Vel(..) => return None,
            MExpr::Neg(a) => -a.value_with(param)?,
            MExpr::Bin(op, a, b) => {
                let (a, b) = (a.value_with(param)?, b.value_with(param)?);
                match op {
                    MBin::Add => a + b,
                    MBin::Sub => a - b,
                    MBin::Mul => a * b,
                    MBin::Div => a / b,
                    MBin::Pow => a.powf(b),
                }
            }
            MExpr::Call(f, a) => {
                let a = a.value_with(param)?;
                match f {
                    Func::Sin => a.sin(),
                    Func::Cos => a.cos(),
                    Func::Tan => a.tan(),
                    Func::Asin => a.asin(),
                    Func::Acos => a.acos(),
                    Func::Atan => a.atan(),
                    Func::Sqrt => a.sqrt(),
                    Func::Exp => a.exp(),
                    Func::Ln => a.ln(),
                }
            }
            MExpr::Atan2(y, x) => y.value_with(param)?.atan2(x.value_with(param)?),
            MExpr::Kink(k, args) => {
                let a: Option<Vec<f64>> = args.iter().map(|a| a.value_with(param)).collect();
                k.apply(&a?)
            }
            MExpr::If(cmp, e) => {
                let [a, b, x, y] = &**e;
                if cmp.holds(a.value_with(param)?, b.value_with(param)?) {
                    x.value_with(param)?
                } else {
                    y.value_with(param)?
                }
            }
        })
    }
}

/// What an expression may refer to, by where it stands.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Scope {
    /// Numbers, `PI` and functions: parameter defaults.
    Constant,
    /// Also parameters: geometry, masses, initial values.
    Params,
    /// Also `t`: drivers.
    Time,
    /// Also coordinates: user constraints.
    State,
    /// Also velocities: forces.
    Force,
}

impl Scope {
    /// What an expression of this scope may use, and why.
    pub(super) fn describe(self) -> &'static str {
        match self {
            Scope::Constant => "numbers, `PI` and functions of them (a parameter's default is a constant)",
            Scope::Params => "numbers, `PI` and parameters (geometry, masses and initial values do not move)",
            Scope::Time => "`t` and parameters (a driver is a function of time)",
            Scope::State => "coordinates, `t` and parameters (a constraint does not depend on velocities)",
            Scope::Force => "",
        }
    }
}
