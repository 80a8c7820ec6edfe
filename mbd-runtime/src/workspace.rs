//! Work space of the solvers: every array whose size grows as the square of the mechanism's
//! size, in one value the caller owns and passes to each analysis (as Pinocchio's `Data` sits
//! beside its `Model`).
//!
//! The solvers themselves keep only O(NV + NC) arrays on the stack, so a mechanism of any size
//! runs on an ordinary thread's stack: a 120-link chain (NV = 360, NC = 240) needs 3.3 MB of
//! work space, which [`Workspace::boxed`] (or the generated `Name::workspace()`) puts on the
//! heap once. Without `std`, a [`Workspace::new`] in a `static` serves the same purpose; it is
//! `const`.
//!
//! | field | size | used by |
//! |---|---|---|
//! | constraint Jacobian D | NC × NV | kinematics, assembly, partitioning, inverse dynamics, statics, generalized-α |
//! | a second NC × NV | NC × NV | partitioning (the elimination that chooses the dependent velocities) |
//! | constraint square | NC × NC | minimum-norm assembly steps (D Dᵀ), coordinate partitioning |
//! | a velocity square | NV × NV | inverse dynamics (the LU of Dᵀ) |
//! | a second constraint square | NC × NC | minimum-norm reactions of redundant rows (their coupling to the kept rows) |
//!
//! Statics and generalized-α need none of it: they factor over the sparse pattern `mechanism!`
//! plans, on the stack (O(its non-zeros)). N must be NV + NC (stable Rust cannot compute it
//! from the other two; the solvers that size their planned storage by it check it); the generated
//! `Name::workspace()` gets it right, and the solvers check it
//! ([`crate::SimulationError::WorkspaceSize`], [`crate::StaticError::WorkspaceSize`]).

use crate::Real;

/// A [`Workspace`] on the heap, as [`Workspace::boxed`] and the generated `Name::workspace()`
/// return it.
#[cfg(feature = "std")]
pub type Boxed<T, const NV: usize, const NC: usize, const N: usize> = std::boxed::Box<Workspace<T, NV, NC, N>>;

/// The O(N²) work space of the solvers, for a mechanism with NV velocities and NC constraint
/// rows; N = NV + NC. Its contents between calls mean nothing: every solver writes before it
/// reads. See [the module](self) for what each part holds.
///
/// `repr(C)` and made only of arrays of `T`, so it is exactly `size_of::<Self>() /
/// size_of::<T>()` consecutive scalars, which [`Workspace::boxed`] relies on.
#[repr(C)]
#[derive(Clone, Debug)]
pub struct Workspace<T, const NV: usize, const NC: usize, const N: usize> {
    pub(crate) jacobian: [[T; NV]; NC],
    pub(crate) jacobian_scratch: [[T; NV]; NC],
    pub(crate) constraint_square: [[T; NC]; NC],
    pub(crate) velocity_square: [[T; NV]; NV],
    pub(crate) coupling: [[T; NC]; NC],
}

impl<T: Real, const NV: usize, const NC: usize, const N: usize> Workspace<T, NV, NC, N> {
    /// A zeroed work space, by value: for a `static` (it is `const`) or a small mechanism. A
    /// large one on the stack defeats its purpose; use [`Workspace::boxed`] there.
    pub const fn new() -> Self {
        Self {
            jacobian: [[T::ZERO; NV]; NC],
            jacobian_scratch: [[T::ZERO; NV]; NC],
            constraint_square: [[T::ZERO; NC]; NC],
            velocity_square: [[T::ZERO; NV]; NV],
            coupling: [[T::ZERO; NC]; NC],
        }
    }

    /// Bytes of work space (the whole value).
    pub const BYTES: usize = core::mem::size_of::<Self>();

    /// The constraint Jacobian D = Φ_q B as the last solve that evaluated it left it: after
    /// [`crate::inverse_dynamics`] and after a successful [`crate::StaticSolver::solve`], D(q, t)
    /// at the q and t they return (what [`crate::joint_reaction`] takes); after other solves it
    /// may hold D at another q, or D's LU factors.
    pub fn jacobian(&self) -> &[[T; NV]; NC] {
        &self.jacobian
    }

    /// A zeroed work space built directly on the heap: `Box::new(Workspace::new())` would
    /// build it on the stack first (in a debug build, or whenever the copy is not elided),
    /// which is what the heap is for avoiding.
    #[cfg(feature = "std")]
    pub fn boxed() -> std::boxed::Box<Self> {
        let mut uninit = std::boxed::Box::<Self>::new_uninit();
        let first = uninit.as_mut_ptr().cast::<T>();
        let scalars = if core::mem::size_of::<T>() == 0 { 0 } else { Self::BYTES / core::mem::size_of::<T>() };
        // SAFETY: `Self` is `repr(C)` and consists only of arrays of `T`, all with T's
        // alignment, so it is `scalars` consecutive, properly aligned `T`s with no padding;
        // writing each one initializes every field (T is `Copy`, so nothing is dropped).
        unsafe {
            for k in 0..scalars {
                first.add(k).write(T::ZERO);
            }
            uninit.assume_init()
        }
    }
}

impl<T: Real, const NV: usize, const NC: usize, const N: usize> Default for Workspace<T, NV, NC, N> {
    fn default() -> Self {
        Self::new()
    }
}

#[cfg(all(test, feature = "std"))]
mod tests {
    use super::Workspace;

    /// The boxed work space is the zeroed one, every field.
    #[test]
    fn boxed_is_zeroed() {
        let boxed = Workspace::<f64, 3, 2, 5>::boxed();
        let value = Workspace::<f64, 3, 2, 5>::new();
        assert_eq!(format!("{boxed:?}"), format!("{value:?}"));
        assert_eq!(Workspace::<f64, 3, 2, 5>::BYTES, 8 * (2 * 2 * 3 + 2 * 2 * 2 + 3 * 3));
    }

    /// A work space far larger than a thread's stack is built on the heap (a copy through the
    /// stack would overflow this 256 KB thread).
    #[test]
    fn boxed_does_not_pass_through_the_stack() {
        let handle = std::thread::Builder::new()
            .stack_size(256 << 10)
            .spawn(|| {
                let ws = Workspace::<f64, 120, 80, 200>::boxed();
                ws.coupling[79][79] + ws.jacobian[79][119]
            })
            .unwrap();
        assert_eq!(handle.join().unwrap(), 0.0);
    }
}
