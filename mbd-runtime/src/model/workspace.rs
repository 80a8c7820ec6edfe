//! Work space of the solvers: every array whose size grows as the square of the mechanism's
//! size, and the planned sparse Newton matrices, in one value the caller owns and passes to each
//! analysis (as Pinocchio's `Data` sits beside its `Model`).
//!
//! The solvers' O(NV + NC) vectors are here too (rows of N scalars: the integrators' stages and
//! Newton corrections, statics' iterate, and the three points a simulation steps between), and
//! so are the generated forward dynamics' arrays where they are more than 2 048 scalars (D's
//! non-zeros in the second NC × NV array, the factor of S = D M⁻¹ Dᵀ in the NC × NC one, which
//! body coordinates do not use otherwise, and Φ, ν, γ, h and M⁻¹ in the rows), so that a solver's
//! frame does not grow with the mechanism; so are the dense LUs' row indices and coordinate
//! partitioning's choice. What stays on the stack grows by a few scalars a velocity: the sample
//! handed to a simulation's callback (a value the callback may keep), the generated functions'
//! temporaries, an interpolation's two rates of q, flags of a byte a row, and cold error paths.
//! Measured by painting the stack (2026-12-07), a simulation of a 201-body ladder (NV = 603)
//! takes 25–38 KiB in a release build (29 KiB with partitioning) and 79–139 KiB in a debug one;
//! in release, 14–24 KiB more than a 51-body one (NV = 153), 14 KiB of which is the sample. It
//! took 33–67 KiB earlier that day, 141 and 318–389 KiB on 2026-12-06, 283–434 and 769–1 059
//! before; assembly takes 15 and 27 KiB, statics 16 and 38 KiB. Where they are needed at all,
//! the O(N²) arrays are here: a 120-link chain (NV = 360, NC = 240) needs 3.6 MB of work space,
//! which [`Workspace::boxed`] (or the generated `Name::workspace()`) puts on the heap once.
//! Without `std`, a [`Workspace::new`] in a `static` serves the same purpose; it is
//! `const`.
//!
//! | field | size | used by |
//! |---|---|---|
//! | constraint Jacobian D | NC × NV | kinematics, assembly, partitioning, inverse dynamics, statics, generalized-α |
//! | a second NC × NV | NC × NV | partitioning (the elimination that chooses the dependent velocities) |
//! | constraint square | NC × NC | minimum-norm assembly steps (D Dᵀ), coordinate partitioning |
//! | a velocity square | NV × NV | inverse dynamics (the LU of Dᵀ) |
//! | a second constraint square | NC × NC | minimum-norm reactions of redundant rows (their coupling to the kept rows) |
//! | (the four above, as [`DenseScratch`]) | | where M depends on q (joint coordinates): forward dynamics and projections with constraint rows, and the Newton matrices of statics, generalized-α and BDF (A and D here, the second NV × NV in the Newton slot being filled); in body coordinates, past 2 048 scalars, the generated forward dynamics' D non-zeros (in the second NC × NV) and factor of S (in the constraint square) |
//! | the solvers' vectors | 48 × (NV + NC) | the integrators' stages, residuals and Newton corrections; statics' iterate |
//! | a simulation's points | 12 × (NV + NC) | the step's start, its end, and the end the integrator left (three `Point`s) |
//! | the solvers' indices | 4 NC + 2 NV (`usize`) | the dense LUs' row interchanges and scratch; coordinate partitioning's dependent velocities and rows, kept from step to step |
//! | three planned Newton matrices | 3 × NS | statics (the mass matrix [[M, −Dᵀ], [D, 0]], the stiffness matrix [[M − H, −Dᵀ], [D, 0]], and factors), generalized-α (its iteration matrix) |
//!
//! Statics and generalized-α factor over the sparse pattern `mechanism!` plans; each matrix is
//! NS = `Name::NEWTON_STORAGE` scalars (D's non-zeros and the factors' entries, fill included),
//! kept here rather than on the stack, where statics' dozen copies of it and generalized-α's one
//! had overflowed a 2 MB thread for a 201-body ladder in a debug build (`tests/large.rs` runs it
//! there now).
//!
//! N must be NV + NC and NS the mechanism's `NEWTON_STORAGE` (stable Rust cannot compute them
//! from the others); the generated `Name::workspace()` gets them right, and the solvers check
//! them ([`crate::SimulationError::WorkspaceSize`], [`crate::StaticError::WorkspaceSize`]). A
//! work space with NS = 0 (the default) serves every solver but statics and generalized-α.

use crate::real::Real;

/// A [`Workspace`] on the heap, as [`Workspace::boxed`] and the generated `Name::workspace()`
/// return it.
#[cfg(feature = "std")]
pub type Boxed<T, const NV: usize, const NC: usize, const N: usize, const NS: usize = 0> = std::boxed::Box<Workspace<T, NV, NC, N, NS>>;

/// The O(N²) work space of the solvers, for a mechanism with NV velocities and NC constraint
/// rows; N = NV + NC, NS the size of its planned Newton matrix (`Name::NEWTON_STORAGE`). Its contents between calls mean nothing: every solver writes before it
/// reads. See [the module](self) for what each part holds.
///
/// It is the solvers' arrays ([`WorkArrays`], which it dereferences to) and the three points a
/// [`Simulation`](crate::Simulation) steps between (the step's start, its end and the end as
/// the integrator left it). An [`Integrator`](crate::Integrator) gets the arrays alone, beside
/// the points.
///
/// `repr(C)`, made of arrays of `T` and of `usize` (the solvers' indices), which
/// [`Workspace::boxed`] writes field by field.
#[repr(C)]
#[derive(Clone, Debug)]
pub struct Workspace<T, const NV: usize, const NC: usize, const N: usize, const NS: usize = 0> {
    pub(crate) arrays: WorkArrays<T, NV, NC, N, NS>,
    pub(crate) points: Rows<T, NV, NC, POINT_ROWS>,
}

/// The solvers' arrays of a [`Workspace`] (see [the module](self)): what an
/// [`Integrator`](crate::Integrator) step is given, apart from the points it steps between.
#[repr(C)]
#[derive(Clone, Debug)]
pub struct WorkArrays<T, const NV: usize, const NC: usize, const N: usize, const NS: usize = 0> {
    pub(crate) jacobian: [[T; NV]; NC],
    pub(crate) jacobian_scratch: [[T; NV]; NC],
    pub(crate) constraint_square: [[T; NC]; NC],
    pub(crate) velocity_square: [[T; NV]; NV],
    pub(crate) coupling: [[T; NC]; NC],
    pub(crate) newton: [[T; NS]; 3],
    pub(crate) vectors: Rows<T, NV, NC, VECTOR_ROWS>,
    pub(crate) indices: Indices<NV, NC>,
}

/// The solvers' row and column indices: the dense LUs' interchanges and scratch
/// ([`crate::linalg::LuWork`]), and coordinate partitioning's choice, which a simulation keeps
/// from one step to the next.
#[repr(C)]
#[derive(Clone, Debug)]
pub(crate) struct Indices<const NV: usize, const NC: usize> {
    /// The interchanges of an LU with NC rows: D where it is square (kinematics), D Dᵀ + μ I
    /// (a failed assembly's descent), partitioning's D_d.
    pub(crate) pivots_c: [usize; NC],
    /// The interchanges of an LU with NV rows: Dᵀ (inverse dynamics), the Hessian of a failed
    /// assembly's descent.
    pub(crate) pivots_v: [usize; NV],
    /// An LU's scratch (the pivot row's non-zero columns), NC columns and NV columns.
    pub(crate) columns_c: [usize; NC],
    pub(crate) columns_v: [usize; NV],
    /// Partitioning's dependent velocities, and its constraint rows in pivot order
    /// ([`crate::Partition`]).
    pub(crate) dependent: [usize; NC],
    pub(crate) rows: [usize; NC],
}

impl<const NV: usize, const NC: usize> Indices<NV, NC> {
    const fn new() -> Self {
        Self { pivots_c: [0; NC], pivots_v: [0; NV], columns_c: [0; NC], columns_v: [0; NV], dependent: [0; NC], rows: [0; NC] }
    }
}

/// K rows of NV scalars and K of NC: K (NV + NC) consecutive scalars, whatever the work space's
/// N (a work space with N = 0, which the explicit integrators accept, has them too).
///
/// `repr(C)` and made only of arrays of `T`, as the [`Workspace`] holding it.
#[repr(C)]
#[derive(Clone, Debug)]
pub(crate) struct Rows<T, const NV: usize, const NC: usize, const K: usize> {
    v: [[T; NV]; K],
    c: [[T; NC]; K],
}

impl<T: Real, const NV: usize, const NC: usize, const K: usize> Rows<T, NV, NC, K> {
    const fn new() -> Self {
        Self { v: [[T::ZERO; NV]; K], c: [[T::ZERO; NC]; K] }
    }
}

impl<T, const NV: usize, const NC: usize, const K: usize> Rows<T, NV, NC, K> {
    /// The rows as one slice of K (NV + NC) scalars.
    pub(crate) fn flat(&mut self) -> &mut [T] {
        let scalars = if core::mem::size_of::<T>() == 0 { 0 } else { core::mem::size_of::<Self>() / core::mem::size_of::<T>() };
        // SAFETY: `Self` is `repr(C)` with two fields, each an array of arrays of `T`, all with
        // T's alignment and sizes that are multiples of it: no padding, so it is `scalars`
        // consecutive initialized `T`s, borrowed mutably for the result's lifetime.
        unsafe { core::slice::from_raw_parts_mut((self as *mut Self).cast::<T>(), scalars) }
    }
}

/// Rows of NV + NC scalars for a [`Simulation`](crate::Simulation)'s three points: a point is
/// 5 + NQ + 2 NV + NC scalars, so they fit where 15 + 3 NQ ≤ 6 NV + 9 NC (every mechanism with
/// NQ ≤ 4/3 NV and 2 NV + 9 NC ≥ 15); smaller ones keep their points on the stack.
pub(crate) const POINT_ROWS: usize = 12;

impl<T: Real, const NV: usize, const NC: usize, const N: usize, const NS: usize> Workspace<T, NV, NC, N, NS> {
    /// A zeroed work space, by value: for a `static` (it is `const`) or a small mechanism. A
    /// large one on the stack defeats its purpose; use [`Workspace::boxed`] there.
    pub const fn new() -> Self {
        Self {
            arrays: WorkArrays {
                jacobian: [[T::ZERO; NV]; NC],
                jacobian_scratch: [[T::ZERO; NV]; NC],
                constraint_square: [[T::ZERO; NC]; NC],
                velocity_square: [[T::ZERO; NV]; NV],
                coupling: [[T::ZERO; NC]; NC],
                newton: [[T::ZERO; NS]; 3],
                vectors: Rows::new(),
                indices: Indices::new(),
            },
            points: Rows::new(),
        }
    }

    /// Bytes of work space (the whole value).
    pub const BYTES: usize = core::mem::size_of::<Self>();

    /// A zeroed work space built directly on the heap: `Box::new(Workspace::new())` would
    /// build it on the stack first (in a debug build, or whenever the copy is not elided),
    /// which is what the heap is for avoiding.
    #[cfg(feature = "std")]
    pub fn boxed() -> std::boxed::Box<Self> {
        let mut uninit = std::boxed::Box::<Self>::new_uninit();
        let this = uninit.as_mut_ptr();
        // SAFETY: every field of `Self` is written in place (through raw pointers to the
        // fields, no reference to uninitialized memory): its arrays of `T` scalar by scalar
        // with `T::ZERO` (T is `Copy`: nothing is dropped) and its indices with zero bytes,
        // which are the `usize` value 0. Then it is initialized.
        unsafe {
            let arrays = &raw mut (*this).arrays;
            fill_zero::<T, _>(&raw mut (*arrays).jacobian);
            fill_zero::<T, _>(&raw mut (*arrays).jacobian_scratch);
            fill_zero::<T, _>(&raw mut (*arrays).constraint_square);
            fill_zero::<T, _>(&raw mut (*arrays).velocity_square);
            fill_zero::<T, _>(&raw mut (*arrays).coupling);
            fill_zero::<T, _>(&raw mut (*arrays).newton);
            fill_zero::<T, _>(&raw mut (*arrays).vectors);
            (&raw mut (*arrays).indices).write_bytes(0, 1);
            fill_zero::<T, _>(&raw mut (*this).points);
            uninit.assume_init()
        }
    }

    /// The solvers' arrays, and apart from them the rows of scalars that hold a simulation's
    /// points ([`POINT_ROWS`]).
    pub(crate) fn arrays_and_points(&mut self) -> (&mut WorkArrays<T, NV, NC, N, NS>, &mut [T]) {
        let Self { arrays, points } = self;
        (arrays, points.flat())
    }
}

/// Writes `T::ZERO` over every scalar of `*place`.
///
/// # Safety
/// `place` is valid for writes and `A` consists only of `T`s: an array of `T`, of arrays of
/// them, or a `repr(C)` struct of such arrays (so it is `size_of::<A>() / size_of::<T>()`
/// consecutive, aligned `T`s with no padding).
#[cfg(feature = "std")]
unsafe fn fill_zero<T: Real, A>(place: *mut A) {
    let first = place.cast::<T>();
    let scalars = if core::mem::size_of::<T>() == 0 { 0 } else { core::mem::size_of::<A>() / core::mem::size_of::<T>() };
    for k in 0..scalars {
        // SAFETY: k < scalars, within `*place` (the caller's guarantee).
        unsafe { first.add(k).write(T::ZERO) }
    }
}

impl<T, const NV: usize, const NC: usize, const N: usize, const NS: usize> WorkArrays<T, NV, NC, N, NS> {
    /// The constraint Jacobian D = Φ_q B as the last solve that evaluated it left it: after
    /// [`crate::InverseDynamics::solve`] and after a successful [`crate::StaticSolver::solve`], D(q, t)
    /// at the q and t they return (what [`crate::joint_reaction`] takes); after other solves it
    /// may hold D at another q, or D's LU factors.
    pub fn jacobian(&self) -> &[[T; NV]; NC] {
        &self.jacobian
    }
}

impl<T, const NV: usize, const NC: usize, const N: usize, const NS: usize> core::ops::Deref for Workspace<T, NV, NC, N, NS> {
    type Target = WorkArrays<T, NV, NC, N, NS>;

    fn deref(&self) -> &Self::Target {
        &self.arrays
    }
}

impl<T, const NV: usize, const NC: usize, const N: usize, const NS: usize> core::ops::DerefMut for Workspace<T, NV, NC, N, NS> {
    fn deref_mut(&mut self) -> &mut Self::Target {
        &mut self.arrays
    }
}

/// Rows of N = NV + NC scalars in a [`Workspace`] for the solvers' vectors ([`Vectors`]): the
/// deepest chain of calls (a Radau5 step with its stages, residuals and error estimate) takes
/// fewer than this many rows' worth of q-, v- and λ-sized vectors (q counts as two rows where
/// NQ > NV), which `tests/large.rs` runs on every analysis.
pub(crate) const VECTOR_ROWS: usize = 48;

/// The solvers' O(NQ + NV + NC) vectors (stages, residuals, corrections), taken from a work
/// space's rows in turn ([`Vectors::take`]) rather than declared on the stack, so that a
/// solver's frame does not grow with the mechanism. A callee gets the rest
/// ([`Vectors::reborrow`]); what it takes is free again when it returns, as a stack frame's
/// locals are.
#[doc(hidden)]
pub struct Vectors<'a, T> {
    free: &'a mut [T],
}

impl<'a, T> Vectors<'a, T> {
    /// Vectors from `storage`.
    pub(crate) fn new(storage: &'a mut [T]) -> Self {
        Self { free: storage }
    }
}

impl<'a, T: Real> Vectors<'a, T> {
    /// A zeroed vector of L scalars, kept until this value's lifetime ends.
    ///
    /// # Panics
    /// If fewer than L scalars are left: the work space's [`VECTOR_ROWS`] do not cover the call
    /// chain, a defect of this crate (the chains are bounded, and their depth is tested).
    pub fn take<const L: usize>(&mut self) -> &'a mut [T; L] {
        let free = core::mem::take(&mut self.free);
        assert!(free.len() >= L, "mbd: the work space's vectors do not cover this solver's calls (a defect: VECTOR_ROWS)");
        let (head, rest) = free.split_at_mut(L);
        self.free = rest;
        head.fill(T::ZERO);
        head.try_into().expect("split at L")
    }

    /// A vector of L scalars holding what the last caller left in it, for one the caller writes
    /// whole before it reads it (as [`rows_written`](Self::rows_written)).
    ///
    /// # Panics
    /// As [`take`](Self::take).
    pub fn take_written<const L: usize>(&mut self) -> &'a mut [T; L] {
        let [vector] = self.rows_written::<L, 1>();
        vector
    }

    /// K zeroed vectors of L scalars, as [`take`](Self::take).
    pub(crate) fn rows<const L: usize, const K: usize>(&mut self) -> &'a mut [[T; L]; K] {
        let rows = self.rows_written::<L, K>();
        rows.as_flattened_mut().fill(T::ZERO);
        rows
    }

    /// K vectors of L scalars holding what the last caller left in them: for vectors the caller
    /// writes whole before it reads them (an output of Φ, h, M x or q̇, a copy), which a zeroed
    /// take would write twice (the small mechanisms' implicit steps spent 3–7 % more time so).
    pub(crate) fn rows_written<const L: usize, const K: usize>(&mut self) -> &'a mut [[T; L]; K] {
        let flat = core::mem::take(&mut self.free);
        assert!(flat.len() >= L * K, "mbd: the work space's vectors do not cover this solver's calls (a defect: VECTOR_ROWS)");
        let (head, rest) = flat.split_at_mut(L * K);
        self.free = rest;
        if L == 0 {
            // SAFETY: `[[T; 0]; K]` has size zero, so a dangling (non-null, aligned) pointer is a
            // valid reference to it; `as_chunks_mut` does not take chunks of zero.
            return unsafe { &mut *core::ptr::NonNull::<[[T; L]; K]>::dangling().as_ptr() };
        }
        let (rows, _) = head.as_chunks_mut::<L>();
        rows.try_into().expect("K rows of L")
    }

    /// The vectors not taken yet, for a callee.
    pub(crate) fn reborrow(&mut self) -> Vectors<'_, T> {
        Vectors { free: &mut *self.free }
    }
}

/// The dense arrays of forward dynamics where M depends on q and the mechanism has constraint
/// rows (joint coordinates with closed loops, [`crate::dense_forward`]): D (NC × NV), M⁻¹Dᵀ
/// (NC × NV), the Schur complement S = D M⁻¹ Dᵀ (NC × NC) and M's Cholesky factor (NV × NV),
/// borrowed from a [`Workspace`] ([`WorkArrays::dense`]) so that they live on its heap, not on
/// the stack (a 201-body ladder in joint coordinates needs 0.7 MB of them per call, which a
/// debug build copied three times past a 2 MB thread). Body coordinates, whose forward dynamics
/// is the generated sparse solve, hold that solve's D non-zeros and factor of S in `d` and `s`
/// where its arrays are past 2 048 scalars. With them, the work space's rows for the solvers'
/// O(N) vectors.
pub struct DenseScratch<'a, T, const NV: usize, const NC: usize> {
    pub(crate) d: &'a mut [[T; NV]; NC],
    pub(crate) y: &'a mut [[T; NV]; NC],
    pub(crate) s: &'a mut [[T; NC]; NC],
    pub(crate) l: &'a mut [[T; NV]; NV],
    pub(crate) vectors: Vectors<'a, T>,
}

impl<'a, T, const NV: usize, const NC: usize> DenseScratch<'a, T, NV, NC> {
    /// The same arrays, borrowed again for one more call.
    pub fn reborrow(&mut self) -> DenseScratch<'_, T, NV, NC> {
        DenseScratch { d: self.d, y: self.y, s: self.s, l: self.l, vectors: Vectors { free: &mut *self.vectors.free } }
    }
}

impl<'a, T: Real, const NV: usize, const NC: usize> DenseScratch<'a, T, NV, NC> {
    /// The arrays of a large mechanism's generated sparse forward dynamics (body coordinates,
    /// which do not use the dense arrays otherwise), as the last caller left them (the generated
    /// code writes them whole before it reads them): D's NNZ non-zeros in the NC × NV array, the
    /// NL entries of the factor of S = D M⁻¹ Dᵀ in the NC × NC one, and vectors of V scalars in
    /// all. `None` where the rows left are fewer than V (a [`DenseArrays`] on the
    /// stack, whose caller asked for the stack): the generated code then keeps its arrays there.
    ///
    /// # Panics
    /// Where NNZ > NC NV or NL > NC², which a mechanism's pattern cannot be.
    #[doc(hidden)]
    pub fn __sparse_storage<const NNZ: usize, const NL: usize, const V: usize>(
        self,
    ) -> Option<(&'a mut [T; NNZ], &'a mut [T; NL], Vectors<'a, T>)> {
        let Self { d, s, vectors, .. } = self;
        if vectors.free.len() < V {
            return None;
        }
        let jv: &mut [T; NNZ] = (&mut d.as_flattened_mut()[..NNZ]).try_into().expect("D's non-zeros fit in NC × NV");
        let l: &mut [T; NL] = (&mut s.as_flattened_mut()[..NL]).try_into().expect("S's factor fits in NC × NC");
        Some((jv, l, vectors))
    }
}

/// Owned [`DenseScratch`] arrays, for a call without a work space
/// ([`crate::ForwardDynamics::accelerations`] and the projections): on the stack of that call,
/// as they were before the work space held them, with three rows of NV and three of NC for the
/// solvers' vectors (what [`crate::project`] takes where it runs out of steps, Φ to name the
/// worst row, and [`crate::System::derivatives`] its work tracking's three velocity vectors).
pub struct DenseArrays<T, const NV: usize, const NC: usize> {
    d: [[T; NV]; NC],
    y: [[T; NV]; NC],
    s: [[T; NC]; NC],
    l: [[T; NV]; NV],
    vectors: Rows<T, NV, NC, 3>,
}

impl<T: Real, const NV: usize, const NC: usize> DenseArrays<T, NV, NC> {
    /// Zeroed arrays.
    pub fn new() -> Self {
        Self { d: [[T::ZERO; NV]; NC], y: [[T::ZERO; NV]; NC], s: [[T::ZERO; NC]; NC], l: [[T::ZERO; NV]; NV], vectors: Rows::new() }
    }

    /// The arrays as a scratch.
    pub fn scratch(&mut self) -> DenseScratch<'_, T, NV, NC> {
        DenseScratch { d: &mut self.d, y: &mut self.y, s: &mut self.s, l: &mut self.l, vectors: Vectors::new(self.vectors.flat()) }
    }
}

impl<T: Real, const NV: usize, const NC: usize> Default for DenseArrays<T, NV, NC> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T, const NV: usize, const NC: usize, const N: usize, const NS: usize> WorkArrays<T, NV, NC, N, NS> {
    /// The arrays of dense forward dynamics ([`DenseScratch`]), from this work space's D,
    /// second NC × NV, constraint square and velocity square.
    pub fn dense(&mut self) -> DenseScratch<'_, T, NV, NC> {
        DenseScratch {
            d: &mut self.jacobian_scratch,
            y: &mut self.jacobian,
            s: &mut self.constraint_square,
            l: &mut self.velocity_square,
            vectors: Vectors::new(self.vectors.flat()),
        }
    }

    /// The Newton slots and the dense arrays, borrowed apart (an implicit step needs both).
    pub(crate) fn newton_and_dense(&mut self) -> (&mut [[T; NS]; 3], DenseScratch<'_, T, NV, NC>) {
        let Self { jacobian, jacobian_scratch, constraint_square, velocity_square, newton, vectors, .. } = self;
        let vectors = Vectors::new(vectors.flat());
        (newton, DenseScratch { d: jacobian_scratch, y: jacobian, s: constraint_square, l: velocity_square, vectors })
    }
}

/// A work space's three Newton-matrix slots (`&mut ws.newton`, borrowed apart from its other
/// fields) as the mechanism's storage type `S` (`[T; NS]`), or `None` where NS is not its size.
pub(crate) fn newton_slots<S: NewtonStorage<T>, T, const NS: usize>(newton: &mut [[T; NS]; 3]) -> Option<[&mut S; 3]> {
    let [a, b, c] = newton;
    Some([S::from_slice_mut(a)?, S::from_slice_mut(b)?, S::from_slice_mut(c)?])
}

/// The storage of a planned Newton matrix, `[T; K]` (`NewtonMatrix::NewtonStorage`): values
/// that can be viewed in place from a work space's slot of exactly K scalars.
pub trait NewtonStorage<T>: Copy + AsRef<[T]> + AsMut<[T]> {
    /// `slice` as this storage, if its length is this storage's.
    fn from_slice_mut(slice: &mut [T]) -> Option<&mut Self>;
}

impl<T: Copy, const K: usize> NewtonStorage<T> for [T; K] {
    fn from_slice_mut(slice: &mut [T]) -> Option<&mut Self> {
        slice.try_into().ok()
    }
}

impl<T: Real, const NV: usize, const NC: usize, const N: usize, const NS: usize> Default for Workspace<T, NV, NC, N, NS> {
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
        // The O(N²) arrays, the rows, and six index arrays (four of NC, two of NV).
        assert_eq!(
            Workspace::<f64, 3, 2, 5>::BYTES,
            8 * (2 * 2 * 3 + 2 * 2 * 2 + 3 * 3 + (super::VECTOR_ROWS + super::POINT_ROWS) * 5)
                + core::mem::size_of::<usize>() * (4 * 2 + 2 * 3)
        );
        // In f32 the indices follow the scalars at usize's alignment.
        let boxed = Workspace::<f32, 3, 2, 5>::boxed();
        assert_eq!(format!("{boxed:?}"), format!("{:?}", Workspace::<f32, 3, 2, 5>::new()));
    }

    /// The Newton slots are views of exactly NS scalars, and only for storage of that size.
    #[test]
    fn newton_slots_fit_their_storage_exactly() {
        let mut ws = Workspace::<f64, 3, 2, 5, 4>::new();
        assert_eq!(Workspace::<f64, 3, 2, 5, 4>::BYTES, Workspace::<f64, 3, 2, 5>::BYTES + 8 * 3 * 4);
        let [a, b, c] = super::newton_slots::<[f64; 4], f64, 4>(&mut ws.newton).expect("NS = 4 fits [f64; 4]");
        (a[3], b[0], c[1]) = (1.0, 2.0, 3.0);
        assert_eq!(ws.newton, [[0.0, 0.0, 0.0, 1.0], [2.0, 0.0, 0.0, 0.0], [0.0, 3.0, 0.0, 0.0]]);
        assert!(super::newton_slots::<[f64; 3], f64, 4>(&mut ws.newton).is_none());
        assert!(super::newton_slots::<[f64; 5], f64, 4>(&mut ws.newton).is_none());
    }

    /// The vectors are taken in turn, zeroed, each disjoint from the others; what a callee
    /// takes from a reborrow is free again after it; zero-length rows take nothing.
    #[test]
    fn vectors_are_taken_in_turn_and_given_back_by_callees() {
        let mut storage = [7.0; 10];
        let mut vectors = super::Vectors::new(&mut storage);
        let a = vectors.take::<3>();
        assert_eq!(*a, [0.0; 3], "zeroed");
        a[0] = 1.0;
        {
            let mut callee = vectors.reborrow();
            let [b, c] = callee.rows::<2, 2>();
            (b[0], c[1]) = (2.0, 3.0);
            assert_eq!(callee.free.len(), 3);
        }
        assert_eq!(vectors.free.len(), 7, "the callee's rows are free again");
        let none: &mut [[f64; 0]; 4] = vectors.rows::<0, 4>();
        assert_eq!(none.len(), 4);
        let d = vectors.take::<7>();
        assert_eq!(*d, [0.0; 7], "rewritten with zeros where the callee wrote");
        assert_eq!(a[0], 1.0, "the first vector is untouched");
    }

    /// Taking past the rows is a defect of this crate, caught loudly.
    #[test]
    #[should_panic(expected = "VECTOR_ROWS")]
    fn vectors_past_the_rows_panic() {
        let mut storage = [0.0; 4];
        let mut vectors = super::Vectors::new(&mut storage);
        let _ = vectors.take::<3>();
        let _ = vectors.take::<2>();
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
